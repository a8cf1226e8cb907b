#pragma once
// Filling summed-area tables with extinction. Every table in the SAT
// techniques integrates the shadow transfer function's sigma_t of the
// trilinearly interpolated volume, zero outside the volume box and the clip
// planes, point-sampled at cell centres (the "discrete positions x_ijk" of
// Ament et al. 2014, eq. 12).
#include "penumbra/render/render_view.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"

#include <string>

namespace penumbra {

// sigma_t at a world position as shadows see it. Empty macrocells return 0
// without sampling the volume (their majorant is a conservative bound).
template <class Sampler> struct ExtinctionField {
  const RenderView* view;
  Sampler sampler;

  PENUMBRA_HD float operator()(vec3 world) const {
    const RenderView& v = *view;
    if (!v.box.contains(world) || !inside_clip_planes(world, v.clip_planes, v.clip_plane_count)) return 0.0f;
    const vec3 index = v.volume.index_from_world(world);
    if (v.majorant_at(index) <= 0.0f) return 0.0f;
    return v.tf.lookup(sampler(index)).a;
  }
};

// A table on `grid` whose cell (i, j, k) holds sigma_t * cell^3 at its centre,
// so a box sum is the extinction integral over the box (world units).
// `what` names the table in memory-budget errors.
SummedAreaTable build_extinction_table(const RenderView& shadows, const CartesianTableGrid& grid,
                                       const std::string& what);

}  // namespace penumbra
