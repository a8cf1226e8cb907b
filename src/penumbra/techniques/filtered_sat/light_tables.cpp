#include "penumbra/techniques/filtered_sat/light_tables.h"

#include "penumbra/techniques/filtered_sat/orthodirectional_groups.h"
#include "penumbra/techniques/sat_common/extinction_table.h"

#include <fmt/format.h>

namespace penumbra {

void LightTables::clear() {
  tables_.clear();
  placements_.clear();
  ids_.clear();
  lookups_.clear();
  light_table_ids_.clear();
}

int LightTables::build(const RenderView& shadows, const std::vector<Light>& lights, float cell, bool reuse) {
  // Plan: one CSAT per orthodirectional group, one SSAT per point light,
  // and which table each light reads.
  std::vector<int> directional;
  std::vector<vec3> to_light;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type == LightType::Directional || l.type == LightType::Distant) {
      directional.push_back(int(i));
      to_light.push_back(-l.direction);
    }
  }
  const OrthodirectionalGrouping grouping = group_orthodirectional(to_light);
  std::vector<Placement> wanted;
  std::vector<int> light_table(lights.size(), -1);
  for (const OrthodirectionalGroup& g : grouping.groups) {
    Placement p;
    p.kind = LightTableKind::Cartesian;
    for (int a = 0; a < 3; ++a) p.axes[a] = g.axes[a];
    p.cell = cell;
    wanted.push_back(p);
  }
  for (std::size_t m = 0; m < directional.size(); ++m) light_table[std::size_t(directional[m])] = grouping.members[m].group;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type != LightType::Point && l.type != LightType::Sphere && l.type != LightType::Disk) continue;
    Placement p;
    p.kind = LightTableKind::Spherical;
    p.light = l.position;
    p.cell = cell;
    light_table[i] = int(wanted.size());
    wanted.push_back(p);
  }

  // Keep the old tables that are wanted again (each at most once); release
  // the rest before building anything.
  std::vector<SummedAreaTable> old = std::move(tables_);
  std::vector<Placement> old_placements = std::move(placements_);
  std::vector<std::uint64_t> old_ids = std::move(ids_);
  clear();
  std::vector<int> from_old(wanted.size(), -1);
  std::vector<bool> taken(old.size(), false);
  if (reuse) {
    for (std::size_t w = 0; w < wanted.size(); ++w) {
      for (std::size_t o = 0; o < old.size(); ++o) {
        if (!taken[o] && old_placements[o] == wanted[w]) {
          taken[o] = true;
          from_old[w] = int(o);
          break;
        }
      }
    }
  }
  for (std::size_t o = 0; o < old.size(); ++o) {
    if (!taken[o]) old[o] = SummedAreaTable();
  }

  // Cells that a surface crosses average points half a voxel apart.
  const int samples = extinction_samples_per_axis(cell / shadows.volume.min_spacing());
  int built = 0;
  tables_.reserve(wanted.size());
  std::vector<CartesianTableGrid> cartesian(wanted.size());
  std::vector<SphericalTableGrid> spherical(wanted.size());
  for (std::size_t w = 0; w < wanted.size(); ++w) {
    const Placement& p = wanted[w];
    if (p.kind == LightTableKind::Cartesian) {
      cartesian[w] = fit_cartesian_grid(shadows.box, p.axes[0], p.axes[1], p.axes[2], cell);
    } else {
      spherical[w] = fit_spherical_grid(shadows.box, p.light, cell);
    }
    if (from_old[w] >= 0) {
      tables_.push_back(std::move(old[std::size_t(from_old[w])]));
      ids_.push_back(old_ids[std::size_t(from_old[w])]);
    } else if (p.kind == LightTableKind::Cartesian) {
      tables_.push_back(
          build_extinction_table(shadows, cartesian[w], fmt::format("filtered-sat CSAT {}", w), samples));
      ids_.push_back(next_id_++);
      ++built;
    } else {
      tables_.push_back(build_spherical_extinction_table(shadows, spherical[w],
                                                         fmt::format("filtered-sat SSAT {}", w), samples));
      ids_.push_back(next_id_++);
      ++built;
    }
    placements_.push_back(p);
  }

  lookups_.assign(lights.size(), LightTableLookup{});
  light_table_ids_.assign(lights.size(), 0);
  for (std::size_t m = 0; m < directional.size(); ++m) {
    const OrthodirectionalMember& member = grouping.members[m];
    LightTableLookup& lookup = lookups_[std::size_t(directional[m])];
    lookup.kind = LightTableKind::Cartesian;
    lookup.cartesian = cartesian[std::size_t(member.group)];
    lookup.axis = member.axis;
    lookup.sign = member.sign;
  }
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const int t = light_table[i];
    if (t < 0) continue;
    LightTableLookup& lookup = lookups_[i];
    if (wanted[std::size_t(t)].kind == LightTableKind::Spherical) {
      lookup.kind = LightTableKind::Spherical;
      lookup.spherical = spherical[std::size_t(t)];
    }
    lookup.table = tables_[std::size_t(t)].view();
    light_table_ids_[i] = ids_[std::size_t(t)];
  }
  return built;
}

std::uint64_t LightTables::bytes() const {
  std::uint64_t total = 0;
  for (const SummedAreaTable& t : tables_) total += t.bytes();
  return total;
}

}  // namespace penumbra
