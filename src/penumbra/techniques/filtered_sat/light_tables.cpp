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

void LightTables::release(std::size_t light_count) {
  clear();
  lookups_.assign(light_count, LightTableLookup{});
  light_table_ids_.assign(light_count, 0);
}

namespace {

// The tables the lights need (one CSAT per orthodirectional group, one SSAT
// per point light), which one each light reads (-1: none), and the
// grouping of the directional lights (their indices in `directional`).
struct TablePlan {
  std::vector<LightTables::Placement> wanted;
  std::vector<int> light_table;
  std::vector<int> directional;
  OrthodirectionalGrouping grouping;
};

TablePlan plan_tables(const std::vector<Light>& lights, float cell) {
  TablePlan plan;
  std::vector<vec3> to_light;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type == LightType::Directional || l.type == LightType::Distant) {
      plan.directional.push_back(int(i));
      to_light.push_back(-l.direction);
    }
  }
  plan.grouping = group_orthodirectional(to_light);
  plan.light_table.assign(lights.size(), -1);
  for (const OrthodirectionalGroup& g : plan.grouping.groups) {
    LightTables::Placement p;
    p.kind = LightTableKind::Cartesian;
    for (int a = 0; a < 3; ++a) p.axes[a] = g.axes[a];
    p.cell = cell;
    plan.wanted.push_back(p);
  }
  for (std::size_t m = 0; m < plan.directional.size(); ++m) {
    plan.light_table[std::size_t(plan.directional[m])] = plan.grouping.members[m].group;
  }
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type != LightType::Point && l.type != LightType::Sphere && l.type != LightType::Disk) continue;
    LightTables::Placement p;
    p.kind = LightTableKind::Spherical;
    p.light = l.position;
    p.cell = cell;
    plan.light_table[i] = int(plan.wanted.size());
    plan.wanted.push_back(p);
  }
  return plan;
}

}  // namespace

std::vector<LightTables::Placement> LightTables::plan(const std::vector<Light>& lights, float cell) {
  const TablePlan p = plan_tables(lights, cell);
  std::vector<Placement> per_light(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (p.light_table[i] >= 0) per_light[i] = p.wanted[std::size_t(p.light_table[i])];
  }
  return per_light;
}

int LightTables::build(const RenderView& shadows, const std::vector<Light>& lights, float cell, bool reuse,
                       int only_light) {
  TablePlan plan = plan_tables(lights, cell);
  std::vector<Placement>& wanted = plan.wanted;
  std::vector<int>& light_table = plan.light_table;
  const std::vector<int>& directional = plan.directional;
  const OrthodirectionalGrouping& grouping = plan.grouping;
  if (only_light >= 0) {
    // Only the table of that light: the others' lights read none.
    const int keep = light_table[std::size_t(only_light)];
    for (int& t : light_table) t = t == keep && keep >= 0 ? 0 : -1;
    wanted = keep >= 0 ? std::vector<Placement>{wanted[std::size_t(keep)]} : std::vector<Placement>{};
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
      tables_.push_back(build_extinction_table(
          shadows, cartesian[w], fmt::format("filtered-sat CSAT {} (sat_resolution sets its size)", w), samples));
      ids_.push_back(next_id_++);
      ++built;
    } else {
      tables_.push_back(build_spherical_extinction_table(
          shadows, spherical[w], fmt::format("filtered-sat SSAT {} (sat_resolution sets its size)", w), samples));
      ids_.push_back(next_id_++);
      ++built;
    }
    placements_.push_back(p);
  }

  lookups_.assign(lights.size(), LightTableLookup{});
  light_table_ids_.assign(lights.size(), 0);
  for (std::size_t m = 0; m < directional.size(); ++m) {
    const OrthodirectionalMember& member = grouping.members[m];
    if (light_table[std::size_t(directional[m])] < 0) continue;
    LightTableLookup& lookup = lookups_[std::size_t(directional[m])];
    lookup.kind = LightTableKind::Cartesian;
    lookup.cartesian = cartesian[std::size_t(light_table[std::size_t(directional[m])])];
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

LightTableLookup LightTables::lookup_without_table(const Box3& box, const std::vector<Light>& lights, float cell,
                                                   int light) {
  const TablePlan plan = plan_tables(lights, cell);
  LightTableLookup lookup;
  const int t = plan.light_table[std::size_t(light)];
  if (t < 0) return lookup;
  const Placement& p = plan.wanted[std::size_t(t)];
  if (p.kind == LightTableKind::Spherical) {
    lookup.kind = LightTableKind::Spherical;
    lookup.spherical = fit_spherical_grid(box, p.light, cell);
    return lookup;
  }
  for (std::size_t m = 0; m < plan.directional.size(); ++m) {
    if (plan.directional[m] != light) continue;
    lookup.kind = LightTableKind::Cartesian;
    lookup.cartesian = fit_cartesian_grid(box, p.axes[0], p.axes[1], p.axes[2], cell);
    lookup.axis = plan.grouping.members[m].axis;
    lookup.sign = plan.grouping.members[m].sign;
  }
  return lookup;
}

std::uint64_t LightTables::bytes() const {
  std::uint64_t total = 0;
  for (const SummedAreaTable& t : tables_) total += t.bytes();
  return total;
}

}  // namespace penumbra
