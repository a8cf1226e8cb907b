#include "penumbra/render/scene_resources.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

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

namespace {

// Rays march in float from the eye: beyond about 2^20 steps from the scene,
// t + step rounds back to t and a march never advances. Such a camera sees
// the scene as a speck anyway (an orthographic one sees the same from nearer).
constexpr float kMaxEyeDistanceInSteps = float(1 << 20);

void check_camera_distance(const Scene& scene) {
  const Box3 box = scene.scene_box();
  const vec3 eye = scene.camera().eye;
  const float distance = glm::length(glm::max(glm::max(box.lower - eye, eye - box.upper), vec3(0.0f)));
  const float limit = kMaxEyeDistanceInSteps * scene.step_world();
  if (!(distance <= limit)) {
    throw InvalidScene("camera.eye", fmt::format("is {:.4g} away from the scene, farther than the {:.4g} (2^20 ray "
                                                 "steps) that rays can march in float precision; move it closer",
                                                 distance, limit));
  }
}

}  // namespace

RenderView SceneResources::view(const Scene& scene) const {
  check_camera_distance(scene);
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
  r.versions = scene.versions();
  r.device_state = &device_state_;
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
