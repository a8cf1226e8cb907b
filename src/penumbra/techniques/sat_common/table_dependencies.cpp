#include "penumbra/techniques/sat_common/table_dependencies.h"

namespace penumbra {

ExtinctionInputs extinction_inputs(const Scene& scene, const RenderView& shadows) {
  ExtinctionInputs in;
  in.data = scene.versions().data;
  in.sigma.assign(shadows.tf.sigma, shadows.tf.sigma + shadows.tf.size);
  in.value_min = shadows.tf.value_min;
  in.index_scale = shadows.tf.index_scale;
  in.clip_planes = scene.clip_planes();
  return in;
}

LightPlacement light_placement(const Light& light) {
  LightPlacement p;
  p.type = light.type;
  if (light.at_infinity()) {
    if (light.type != LightType::Environment) p.direction = light.direction;
  } else {
    p.position = light.position;  // a disk's facing changes its radiance only
  }
  return p;
}

std::vector<LightPlacement> light_placements(const std::vector<Light>& lights) {
  std::vector<LightPlacement> out;
  out.reserve(lights.size());
  for (const Light& l : lights) out.push_back(light_placement(l));
  return out;
}

}  // namespace penumbra
