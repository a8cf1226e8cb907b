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
  // What a table is built from, beside the extinction.
  struct Placement {
    LightTableKind kind = LightTableKind::None;
    vec3 axes[3] = {vec3(0.0f), vec3(0.0f), vec3(0.0f)};  // CSAT frame
    vec3 light{0.0f};                                     // SSAT centre
    float cell = 0.0f;
    bool operator==(const Placement& o) const {
      return kind == o.kind && axes[0] == o.axes[0] && axes[1] == o.axes[1] && axes[2] == o.axes[2] &&
             light == o.light && cell == o.cell;
    }
  };

  // Per light, the placement of the table it reads (kind None: no table),
  // without building anything: two lights with equal placements read one
  // table, and a light whose placement did not change between two builds
  // from the same extinction reads a table equal to the one before.
  static std::vector<Placement> plan(const std::vector<Light>& lights, float cell);

  // Builds every table the lights need from the shadow view's extinction,
  // with cells of `cell` world units. With `reuse`, a table of the last
  // build whose placement (a CSAT's frame, an SSAT's light position) and
  // cell are the same is kept instead of rebuilt: pass it when the
  // extinction (data, shadow TF, clip planes) did not change since. Tables
  // no light needs any more are released before new ones are built. With
  // `only_light` >= 0 only the table that light reads is built (or kept):
  // the other lights' lookups have kind None, so that one table at a time
  // lives while the shadow caches are filled (the paper's future work,
  // section 7). Returns how many tables it built. Throws OutOfMemoryBudget
  // before allocating a table that does not fit.
  int build(const RenderView& shadows, const std::vector<Light>& lights, float cell, bool reuse = false,
            int only_light = -1);
  // The lookup build() would give `light`, without building its table
  // (table empty): the grid of its CSAT (with axis and sign) or SSAT,
  // for filtered-sat's streamed evaluation (streamed_table.h).
  static LightTableLookup lookup_without_table(const Box3& box, const std::vector<Light>& lights, float cell,
                                               int light);
  // Frees every table; `light_count` lookups of kind None remain.
  void release(std::size_t light_count);
  void clear();

  // One per light of the last build, in the scene's order.
  const std::vector<LightTableLookup>& lookups() const { return lookups_; }
  // Per light: an id of the table it reads, new for every table built, so a
  // light whose id did not change sees the same table as before.
  const std::vector<std::uint64_t>& table_ids() const { return light_table_ids_; }
  int table_count() const { return int(tables_.size()); }
  std::uint64_t bytes() const;

 private:
  std::vector<SummedAreaTable> tables_;
  std::vector<Placement> placements_;  // per table
  std::vector<std::uint64_t> ids_;     // per table
  std::vector<LightTableLookup> lookups_;
  std::vector<std::uint64_t> light_table_ids_;  // per light (0: none)
  std::uint64_t next_id_ = 1;
};

}  // namespace penumbra
