#include "penumbra/render/scene_resources.h"

#include "penumbra/base/parallel.h"

namespace penumbra {

std::vector<float> build_majorants(const MacrocellGrid& grid, const TransferFunctionTable& table) {
  const ivec3 d = grid.dims();
  std::vector<float> majorants(static_cast<std::size_t>(d.x) * d.y * d.z);
  const MacrocellView cells = grid.view();
  parallel_for(0, std::int64_t(majorants.size()), [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t i = first; i < last; ++i) {
      const vec2 range = cells.min_max[i];
      majorants[static_cast<std::size_t>(i)] = table.max_extinction(range.x, range.y);
    }
  }, 256);
  return majorants;
}

bool SceneResources::update(const Scene& scene) {
  const SceneVersions& v = scene.versions();
  bool changed = false;
  if (v.data != data_version_) {
    macrocells_ = MacrocellGrid(scene.volume_view());
    data_version_ = v.data;
    tf_version_ = 0;  // the TF range may depend on the data
    changed = true;
  }
  if (v.transfer_function != tf_version_) {
    tf_table_ = TransferFunctionTable(scene.transfer_function(), scene.tf_value_range(), scene.unit_length());
    majorants_ = build_majorants(macrocells_, tf_table_);
    tf_version_ = v.transfer_function;
    changed = true;
  }
  return changed;
}

RenderView SceneResources::view(const Scene& scene) const {
  RenderView r;
  r.volume = scene.volume_view();
  r.macrocells = macrocells_.view();
  r.majorants = majorants_.data();
  r.tf = tf_table_.view();
  r.box = scene.volume().world_box();
  r.clip_planes = scene.clip_planes().data();
  r.clip_plane_count = static_cast<int>(scene.clip_planes().size());
  r.planes = scene.planes().data();
  r.plane_count = static_cast<int>(scene.planes().size());
  r.lights = scene.lights().data();
  r.light_count = static_cast<int>(scene.lights().size());
  r.material = scene.material();
  r.background = scene.background();
  r.step = scene.step_world();
  r.ert_threshold = scene.render().ert_threshold;
  r.jitter = scene.render().jitter;
  r.camera = scene.camera().view();
  r.width = scene.render().width;
  r.height = scene.render().height;
  return r;
}

std::uint64_t SceneResources::bytes() const {
  return macrocells_.bytes() + majorants_.size() * sizeof(float) +
         std::uint64_t(tf_table_.view().size) * sizeof(vec4);
}

}  // namespace penumbra
