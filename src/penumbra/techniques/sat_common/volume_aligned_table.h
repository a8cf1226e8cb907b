#pragma once
// The volume-aligned extinction SAT of the baselines that Ament et al. 2014
// compare against (Schlegel et al. 2011, "Extinction-based shading and
// illumination in GPU volume ray-casting", IEEE TVCG 17(12)): one table on
// the world axes over the volume box, independent of the lights, rebuilt
// when the data (or time step), the shadow TF's extinction, the clip planes
// or the resolution change (not for a floor plane, a light or a render-only
// TF edit).
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"
#include "penumbra/techniques/sat_common/table_dependencies.h"

#include <cstdint>
#include <string>

namespace penumbra {

class VolumeAlignedTable {
 public:
  explicit VolumeAlignedTable(std::string what) : what_(std::move(what)) {}

  // `resolution`: cells per voxel of the smallest spacing (resources
  // updated first). Returns true when it rebuilt.
  bool update(const Scene& scene, const SceneResources& resources, double resolution);

  const CartesianTableGrid& grid() const { return grid_; }
  SummedAreaTableView view() const { return table_.view(); }
  std::uint64_t bytes() const { return table_.bytes(); }

 private:
  std::string what_;
  bool built_ = false;
  ExtinctionInputs inputs_;
  double resolution_ = 0.0;
  CartesianTableGrid grid_;
  SummedAreaTable table_;
};

}  // namespace penumbra
