#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <cmath>

namespace penumbra {

ivec3 visibility_cache_dims(ivec3 data_dims, float resolution) {
  return glm::max(ivec3(glm::ceil(vec3(data_dims) * resolution)), ivec3(2));
}

}  // namespace penumbra
