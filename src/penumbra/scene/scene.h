#pragma once
// Scene: the volume and everything that says how to look at it. Each part has
// a version counter that changes whenever the part is replaced, so a technique
// rebuilds its light-space structures in prepare() only when something it
// depends on changed (a TF change, a light move and a new frame are separately
// measurable costs, as in the papers' tables).
#include "penumbra/base/math.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/scene_versions.h"
#include "penumbra/scene/light.h"
#include "penumbra/scene/material.h"
#include "penumbra/scene/mesh.h"
#include "penumbra/scene/plane.h"
#include "penumbra/scene/transfer_function.h"
#include "penumbra/volume/volume.h"

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace penumbra {

// A technique parameter as written in a scene or on the command line, before
// the technique's parameter table checks it.
using ParameterValue = std::variant<double, bool, std::string>;
using ParameterSettings = std::map<std::string, ParameterValue>;

struct RenderSettings {
  int width = 512;
  int height = 512;
  float step = 0.5f;  // ray-marching step in voxels of the smallest spacing
  std::string technique = "shadow-rays";
  ParameterSettings params;  // for `technique` (see Scene::parameters_for)
  float ert_threshold = 0.99f;  // early ray termination at this accumulated opacity
  bool jitter = false;          // per-pixel random offset of the first sample

  void validate() const;  // throws InvalidScene naming "render.<field>"
};

// Where the scene's volume came from, as a scene file names it: a file path
// (as written, relative to the scene file) or a procedural generator.
struct VolumeSource {
  std::string file;
  std::string builtin;
  ivec3 size{0};
  std::optional<vec3> spacing;  // overrides of the file's values, if given
  std::optional<vec3> origin;
};

class Scene {
 public:
  Scene();

  bool has_volume() const { return volume_ != nullptr; }
  // Throws InvalidScene("volume", ...) when no volume is set.
  const Volume& volume() const;
  const std::shared_ptr<const Volume>& volume_ptr() const { return volume_; }
  void set_volume(std::shared_ptr<const Volume> volume, int time_step = 0);
  const VolumeSource& volume_source() const { return volume_source_; }
  void set_volume_source(VolumeSource source) { volume_source_ = std::move(source); }
  int time_step() const { return time_step_; }
  void set_time_step(int time_step);
  VolumeView volume_view() const { return volume().view(time_step_); }

  const TransferFunction& transfer_function() const { return transfer_function_; }
  void set_transfer_function(TransferFunction tf);
  // A separate TF for light-space structures and shadow rays (generation and
  // rendering may use different TFs, Weidner & Linsen); nullopt = the same TF.
  // Its range and unit length resolve like the main TF's. Changing it bumps
  // the transfer_function version.
  const std::optional<TransferFunction>& shadow_transfer_function() const { return shadow_transfer_function_; }
  void set_shadow_transfer_function(std::optional<TransferFunction> tf);

  const Camera& camera() const { return camera_; }
  void set_camera(Camera camera);

  const std::vector<Light>& lights() const { return lights_; }
  void set_lights(std::vector<Light> lights);

  const Material& material() const { return material_; }
  void set_material(Material material);

  vec3 background() const { return background_; }
  void set_background(vec3 background);

  const std::vector<Plane>& planes() const { return planes_; }
  void set_planes(std::vector<Plane> planes);
  const std::vector<vec4>& clip_planes() const { return clip_planes_; }
  void set_clip_planes(std::vector<vec4> clip_planes);

  // Closed triangle meshes with volumetric detail (mesh.h); only techniques
  // whose TechniqueInfo says draws_meshes draw them.
  const std::vector<MeshObject>& meshes() const { return meshes_; }
  // Throws InvalidScene("meshes[i]...") for a mesh that is missing or invalid,
  // or more than kMaxMeshes of them.
  void set_meshes(std::vector<MeshObject> meshes);
  static constexpr int kMaxMeshes = 32;

  const RenderSettings& render() const { return render_; }
  void set_render(RenderSettings render);

  const SceneVersions& versions() const { return versions_; }

  // Derived quantities every technique uses.
  vec2 tf_value_range() const;   // the TF range in data units
  float unit_length() const;     // the TF's reference length in world units
  // The same for the TF that shadows use (the shadow TF if set, else the TF).
  const TransferFunction& shadow_tf() const;
  vec2 shadow_tf_value_range() const;
  float shadow_unit_length() const;
  float step_world() const;      // render.step in world units
  Box3 scene_box() const;        // the volume's box joined with the meshes' world bounds

 private:
  static std::uint64_t next_version();

  std::shared_ptr<const Volume> volume_;
  VolumeSource volume_source_;
  int time_step_ = 0;
  TransferFunction transfer_function_;
  std::optional<TransferFunction> shadow_transfer_function_;
  Camera camera_;
  std::vector<Light> lights_;
  Material material_;
  vec3 background_{0.0f};
  std::vector<Plane> planes_;
  std::vector<vec4> clip_planes_;
  std::vector<MeshObject> meshes_;
  RenderSettings render_;
  SceneVersions versions_;
};

}  // namespace penumbra
