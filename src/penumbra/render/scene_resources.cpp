#include "penumbra/render/scene_resources.h"

namespace penumbra {

bool SceneResources::update(const Scene& scene, bool normals) {
  const SceneVersions& v = scene.versions();
  bool changed = false;
  if (v.data != data_version_) {
    macrocells_ = MacrocellGrid(scene.volume_view());
    normals_ = NormalVolume();
    data_version_ = v.data;
    tf_version_ = 0;  // the TF range may depend on the data
    changed = true;
  }
  if (v.transfer_function != tf_version_) {
    tf_table_ = TransferFunctionTable(scene.transfer_function(), scene.tf_value_range(), scene.unit_length());
    majorants_ = build_majorant_grid(macrocells_, tf_table_);
    separate_shadow_tf_ = scene.shadow_transfer_function().has_value();
    if (separate_shadow_tf_) {
      shadow_tf_table_ = TransferFunctionTable(scene.shadow_tf(), scene.shadow_tf_value_range(), scene.shadow_unit_length());
      shadow_majorants_ = build_majorant_grid(macrocells_, shadow_tf_table_);
    }
    tf_version_ = v.transfer_function;
    changed = true;
  }
  if (normals && normals_.empty()) {
    normals_ = NormalVolume(scene.volume_view());
  }
  return changed;
}

RenderView SceneResources::view(const Scene& scene) const {
  RenderView r;
  r.volume = scene.volume_view();
  r.macrocells = macrocells_.view();
  r.majorants = majorants_.majorant.data();
  r.empty_distance = majorants_.empty_distance.data();
  r.tf = tf_table_.view();
  r.normals = normals_.view();
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

RenderView SceneResources::shadow_view(const Scene& scene) const {
  RenderView r = view(scene);
  if (separate_shadow_tf_) {
    r.tf = shadow_tf_table_.view();
    r.majorants = shadow_majorants_.majorant.data();
    r.empty_distance = shadow_majorants_.empty_distance.data();
  }
  return r;
}

std::uint64_t SceneResources::bytes() const {
  return macrocells_.bytes() + normals_.bytes() + majorants_.bytes() +
         std::uint64_t(tf_table_.view().size) * sizeof(vec4);
}

}  // namespace penumbra
