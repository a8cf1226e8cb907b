#include "penumbra/techniques/filtered_sat/light_tables.h"

#include "penumbra/techniques/filtered_sat/orthodirectional_groups.h"
#include "penumbra/techniques/sat_common/extinction_table.h"

#include <fmt/format.h>

namespace penumbra {

void LightTables::clear() {
  tables_.clear();
  lookups_.clear();
}

void LightTables::build(const RenderView& shadows, const std::vector<Light>& lights, float cell) {
  clear();
  lookups_.resize(lights.size());
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
  std::size_t point_lights = 0;
  for (const Light& l : lights) {
    point_lights += l.type == LightType::Point || l.type == LightType::Sphere || l.type == LightType::Disk;
  }
  tables_.reserve(grouping.groups.size() + point_lights);  // views into the tables stay valid
  for (std::size_t g = 0; g < grouping.groups.size(); ++g) {
    const vec3* axes = grouping.groups[g].axes;
    const CartesianTableGrid grid = fit_cartesian_grid(shadows.box, axes[0], axes[1], axes[2], cell);
    tables_.push_back(build_extinction_table(shadows, grid, fmt::format("filtered-sat CSAT {}", g)));
    for (std::size_t m = 0; m < directional.size(); ++m) {
      const OrthodirectionalMember& member = grouping.members[m];
      if (member.group != int(g)) continue;
      LightTableLookup& lookup = lookups_[std::size_t(directional[m])];
      lookup.kind = LightTableKind::Cartesian;
      lookup.cartesian = grid;
      lookup.axis = member.axis;
      lookup.sign = member.sign;
      lookup.table = tables_.back().view();
    }
  }
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    if (l.type != LightType::Point && l.type != LightType::Sphere && l.type != LightType::Disk) continue;
    const SphericalTableGrid grid = fit_spherical_grid(shadows.box, l.position, cell);
    tables_.push_back(build_spherical_extinction_table(shadows, grid, fmt::format("filtered-sat SSAT of light {}", i)));
    lookups_[i].kind = LightTableKind::Spherical;
    lookups_[i].spherical = grid;
    lookups_[i].table = tables_.back().view();
  }
}

std::uint64_t LightTables::bytes() const {
  std::uint64_t total = 0;
  for (const SummedAreaTable& t : tables_) total += t.bytes();
  return total;
}

}  // namespace penumbra
