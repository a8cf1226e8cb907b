#include "penumbra/techniques/light_space/light_map.h"

#include "penumbra/base/memory_budget.h"

namespace penumbra {

LightMap::LightMap(const std::string& what, const LightProjection& projection, int values_per_texel)
    : projection_(projection), values_per_texel_(values_per_texel) {
  const std::uint64_t count =
      checked_product({std::uint64_t(projection.texel_count()), std::uint64_t(values_per_texel)});
  check_memory_budget(what, checked_product({count, sizeof(float)}));
  texels_.assign(count, 0.0f);
}

}  // namespace penumbra
