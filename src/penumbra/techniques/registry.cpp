#include "penumbra/techniques/registry.h"

#include "penumbra/base/error.h"
#include "penumbra/techniques/emission_absorption/emission_absorption.h"
#include "penumbra/techniques/phong/phong.h"
#include "penumbra/techniques/pathtrace/pathtrace.h"
#include "penumbra/techniques/shadow_rays/shadow_rays.h"
#include "penumbra/techniques/shadow_map/shadow_map.h"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_map.h"
#include "penumbra/techniques/cssm/cssm.h"
#include "penumbra/techniques/filtered_sat/filtered_sat.h"
#include "penumbra/techniques/sat_ao/sat_ao.h"
#include "penumbra/techniques/cone_shadows/cone_shadows.h"
#include "penumbra/techniques/ipsvi/ipsvi.h"
#include "penumbra/techniques/half_angle/half_angle.h"
#include "penumbra/techniques/occlusion_map/occlusion_map.h"
#include "penumbra/techniques/convolution/convolution.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace penumbra {

const std::vector<TechniqueInfo>& technique_registry() {
  static const std::vector<TechniqueInfo> registry = {
      emission_absorption_info(),
      phong_info(),
      shadow_rays_info(),
      pathtrace_info(),
      shadow_map_info(),
      deep_shadow_map_info(),
      cssm_info(),
      filtered_sat_info(),
      sat_ao_info(),
      cone_shadows_info(),
      ipsvi_info(),
      half_angle_info(),
      occlusion_map_info(),
      convolution_info(),
  };
  return registry;
}

const TechniqueInfo& find_technique(std::string_view name) {
  std::vector<std::string> names;
  for (const TechniqueInfo& info : technique_registry()) {
    if (info.name == name) return info;
    names.push_back(info.name);
  }
  throw InvalidArgument("technique", fmt::format("unknown technique '{}' (known: {})", name, fmt::join(names, ", ")));
}

}  // namespace penumbra
