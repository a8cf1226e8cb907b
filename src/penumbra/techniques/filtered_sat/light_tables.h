#pragma once
// The light-space tables of filtered-sat for one scene: one CSAT per group
// of orthodirectional lights (directional and distant lights, by their
// direction), one SSAT per point light (point, sphere and disk lights, by
// their centre). Environment lights cast no shadow here (they give no
// radiance to the single-scattering techniques). LightTables owns the tables;
// LightTableLookup is the plain per-light view kernels read.
#include "penumbra/render/render_view.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/filtered_sat/csat_lookup.h"
#include "penumbra/techniques/filtered_sat/ssat_lookup.h"

#include <cstdint>
#include <vector>

namespace penumbra {

enum class LightTableKind : std::uint8_t { None, Cartesian, Spherical };

struct LightTableLookup {
  LightTableKind kind = LightTableKind::None;
  SummedAreaTableView table;
  CartesianTableGrid cartesian;  // Cartesian: the light lies toward sign * axes[axis]
  int axis = 2;
  float sign = 1.0f;
  SphericalTableGrid spherical;  // Spherical
};

// Filtered optical depth toward one light (0 for lights without a table).
PENUMBRA_HD inline float filtered_optical_depth(const LightTableLookup& light, const ShadowFilter& filter, vec3 p) {
  switch (light.kind) {
    case LightTableKind::Cartesian:
      return csat_filtered_depth(light.table, light.cartesian, light.axis, light.sign, filter, p);
    case LightTableKind::Spherical: return ssat_filtered_depth(light.table, light.spherical, filter, p);
    case LightTableKind::None: break;
  }
  return 0.0f;
}

class LightTables {
 public:
  // Builds every table the lights need from the shadow view's extinction,
  // with cells of `cell` world units. Throws OutOfMemoryBudget before
  // allocating a table that does not fit.
  void build(const RenderView& shadows, const std::vector<Light>& lights, float cell);
  void clear();

  // One per light of the last build, in the scene's order.
  const std::vector<LightTableLookup>& lookups() const { return lookups_; }
  int table_count() const { return int(tables_.size()); }
  std::uint64_t bytes() const;

 private:
  std::vector<SummedAreaTable> tables_;
  std::vector<LightTableLookup> lookups_;
};

}  // namespace penumbra
