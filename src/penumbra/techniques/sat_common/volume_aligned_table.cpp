#include "penumbra/techniques/sat_common/volume_aligned_table.h"

#include "penumbra/techniques/sat_common/extinction_table.h"

namespace penumbra {

bool VolumeAlignedTable::update(const Scene& scene, const SceneResources& resources, bool shared_changed,
                                double resolution) {
  const std::uint64_t geometry = scene.versions().geometry;
  if (built_ && !shared_changed && geometry == geometry_version_ && resolution == resolution_) return false;
  built_ = false;
  table_ = SummedAreaTable();  // free the old table before building the new one
  const RenderView shadows = resources.shadow_view(scene);
  grid_ = fit_cartesian_grid(shadows.box, vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f),
                             shadows.volume.min_spacing() / float(resolution));
  table_ = build_extinction_table(shadows, grid_, what_);
  built_ = true;
  geometry_version_ = geometry;
  resolution_ = resolution;
  return true;
}

}  // namespace penumbra
