#include "penumbra/techniques/registry.h"

#include "penumbra/backends/device.h"
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
#include "penumbra/techniques/ambient_scattering/ambient_scattering.h"
#include "penumbra/techniques/ipsvi/ipsvi.h"
#include "penumbra/techniques/half_angle/half_angle.h"
#include "penumbra/techniques/occlusion_map/occlusion_map.h"
#include "penumbra/techniques/convolution/convolution.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace penumbra {
namespace {

// The techniques whose frames render on the CUDA device (their Lightings are
// declared with PENUMBRA_DEVICE_LIGHTING and instantiated in a .cu unit).
TechniqueInfo with_cuda_path(TechniqueInfo info) {
  info.has_cuda_path = true;
  return info;
}

// Every technique without one says once, when it is created while CUDA is
// active, that it renders on the CPU.
TechniqueInfo noting_device(TechniqueInfo info) {
  if (!info.has_cuda_path) {
    info.create = [create = info.create, name = info.name] {
      if (active_device() == Device::Cuda) note_cpu_fallback(name.c_str());
      return create();
    };
  }
  return info;
}

}  // namespace

const std::vector<TechniqueInfo>& technique_registry() {
  static const std::vector<TechniqueInfo> registry = [] {
    std::vector<TechniqueInfo> r = {
        with_cuda_path(emission_absorption_info()),
        with_cuda_path(phong_info()),
        with_cuda_path(shadow_rays_info()),
        with_cuda_path(pathtrace_info()),
        with_cuda_path(shadow_map_info()),
        with_cuda_path(deep_shadow_map_info()),
        with_cuda_path(cssm_info()),
        with_cuda_path(filtered_sat_info()),
        with_cuda_path(sat_ao_info()),
        with_cuda_path(cone_shadows_info()),
        with_cuda_path(ambient_scattering_info()),
        ipsvi_info(),
        half_angle_info(),
        with_cuda_path(occlusion_map_info()),
        convolution_info(),
    };
    for (TechniqueInfo& info : r) info = noting_device(std::move(info));
    return r;
  }();
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

void check_technique_prefixes(const ParameterSettings& settings) {
  for (const auto& entry : settings) {
    const auto dot = entry.first.find('.');
    if (dot == std::string::npos) continue;
    const std::string prefix = entry.first.substr(0, dot);
    try {
      find_technique(prefix);
    } catch (const InvalidArgument& e) {
      throw InvalidScene("render.params." + prefix, e.what());
    }
  }
}

}  // namespace penumbra
