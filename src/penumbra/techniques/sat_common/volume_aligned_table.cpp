#include "penumbra/techniques/sat_common/volume_aligned_table.h"

#include "penumbra/techniques/sat_common/extinction_table.h"

namespace penumbra {

bool VolumeAlignedTable::update(const Scene& scene, const SceneResources& resources, double resolution) {
  const RenderView shadows = resources.shadow_view(scene);
  ExtinctionInputs inputs = extinction_inputs(scene, shadows);
  if (built_ && inputs == inputs_ && resolution == resolution_) return false;
  built_ = false;
  table_ = SummedAreaTable();  // free the old table before building the new one
  grid_ = fit_cartesian_grid(shadows.box, vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f),
                             shadows.volume.min_spacing() / float(resolution));
  table_ = build_extinction_table(shadows, grid_, what_);
  built_ = true;
  inputs_ = std::move(inputs);
  resolution_ = resolution;
  return true;
}

}  // namespace penumbra
