#include "penumbra/scene/scene.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <atomic>

namespace penumbra {
namespace {

bool finite3(vec3 v) { return is_finite(v.x) && is_finite(v.y) && is_finite(v.z); }

vec3 unit_vector(vec3 v, const std::string& key) {
  if (!finite3(v)) throw InvalidScene(key, "must be finite");
  const float len = glm::length(v);
  if (!(len > 0.0f)) throw InvalidScene(key, "must not be the zero vector");
  return v / len;
}

void check_colour(vec3 c, const std::string& key) {
  if (!finite3(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) {
    throw InvalidScene(key, "colour components must be finite and >= 0");
  }
}

}  // namespace

void RenderSettings::validate() const {
  if (width <= 0 || height <= 0) {
    throw InvalidScene("render.width", fmt::format("image size must be positive, got {}x{}", width, height));
  }
  if (width > 16384 || height > 16384) {
    throw InvalidScene("render.width", fmt::format("image size {}x{} exceeds 16384 per side", width, height));
  }
  if (!(step >= 0.01f && step <= 64.0f)) {
    throw InvalidScene("render.step", fmt::format("must be in [0.01, 64] voxels, got {}", step));
  }
  if (!(ert_threshold > 0.0f && ert_threshold <= 1.0f)) {
    throw InvalidScene("render.ert_threshold", fmt::format("must be in (0, 1], got {}", ert_threshold));
  }
  if (technique.empty()) throw InvalidScene("render.technique", "must name a technique");
}

std::uint64_t Scene::next_version() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

Scene::Scene() {
  versions_ = SceneVersions{next_version(), next_version(), next_version(), next_version(),
                            next_version(), next_version(), next_version(), next_version()};
}

const Volume& Scene::volume() const {
  if (!volume_) throw InvalidScene("volume", "the scene has no volume");
  return *volume_;
}

void Scene::set_volume(std::shared_ptr<const Volume> volume, int time_step) {
  if (!volume) throw InvalidScene("volume", "must not be null");
  if (time_step < 0 || time_step >= volume->frame_count()) {
    throw InvalidScene("volume.time_step", fmt::format("{} is out of range: the volume has {} time step(s)", time_step,
                                                       volume->frame_count()));
  }
  volume_ = std::move(volume);
  time_step_ = time_step;
  versions_.data = next_version();
}

void Scene::set_time_step(int time_step) {
  if (time_step == time_step_) return;
  set_volume(volume_, time_step);
}

void Scene::set_transfer_function(TransferFunction tf) {
  transfer_function_ = std::move(tf);
  versions_.transfer_function = next_version();
}

void Scene::set_shadow_transfer_function(std::optional<TransferFunction> tf) {
  shadow_transfer_function_ = std::move(tf);
  versions_.transfer_function = next_version();
}

void Scene::set_camera(Camera camera) {
  camera.validate();
  camera_ = camera;
  versions_.camera = next_version();
}

void Scene::set_lights(std::vector<Light> lights) {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Light& l = lights[i];
    const std::string key = fmt::format("lights[{}]", i);
    if (l.type == LightType::Directional || l.type == LightType::Distant || l.type == LightType::Disk) {
      l.direction = unit_vector(l.direction, key + ".direction");
    }
    if (!(l.angle_deg >= 0.0f && l.angle_deg < 90.0f)) {
      throw InvalidScene(key + ".angle_deg", fmt::format("must be in [0, 90), got {}", l.angle_deg));
    }
    // Anisotropy and rotation belong to distant gaussian lights only; a
    // negative angle_y_deg means unset (isotropic).
    const bool gaussian = l.type == LightType::Distant && l.profile == LightProfile::Gaussian;
    if (!(l.angle_y_deg < 0.0f)) {  // set, or NaN
      if (!gaussian) throw InvalidScene(key + ".angle_y_deg", "only a distant light with profile gaussian has one");
      if (!(l.angle_y_deg < 90.0f)) {
        throw InvalidScene(key + ".angle_y_deg", fmt::format("must be in [0, 90), got {}", l.angle_y_deg));
      }
    }
    if (!is_finite(l.rotation_deg)) {
      throw InvalidScene(key + ".rotation_deg", fmt::format("must be finite, got {}", l.rotation_deg));
    }
    if (l.rotation_deg != 0.0f && !gaussian) {
      throw InvalidScene(key + ".rotation_deg", "only a distant light with profile gaussian has one");
    }
    if (!(l.radius >= 0.0f && is_finite(l.radius))) {
      throw InvalidScene(key + ".radius", fmt::format("must be finite and >= 0, got {}", l.radius));
    }
    if (!finite3(l.position)) throw InvalidScene(key + ".position", "must be finite");
    check_colour(l.color, key + ".color");
    if (!(l.intensity >= 0.0f && is_finite(l.intensity))) {
      throw InvalidScene(key + ".intensity", fmt::format("must be finite and >= 0, got {}", l.intensity));
    }
  }
  lights_ = std::move(lights);
  versions_.lights = next_version();
}

void Scene::set_material(Material material) {
  material.validate();
  material_ = material;
  versions_.material = next_version();
}

void Scene::set_background(vec3 background) {
  check_colour(background, "background");
  background_ = background;
  versions_.material = next_version();
}

void Scene::set_planes(std::vector<Plane> planes) {
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const std::string key = fmt::format("planes[{}]", i);
    planes[i].normal = unit_vector(planes[i].normal, key + ".normal");
    if (!finite3(planes[i].point)) throw InvalidScene(key + ".point", "must be finite");
    check_colour(planes[i].color, key + ".color");
  }
  planes_ = std::move(planes);
  versions_.geometry = next_version();
}

void Scene::set_clip_planes(std::vector<vec4> clip_planes) {
  for (std::size_t i = 0; i < clip_planes.size(); ++i) {
    vec4& c = clip_planes[i];
    const std::string key = fmt::format("clip_planes[{}]", i);
    if (!finite3(vec3(c)) || !is_finite(c.w)) throw InvalidScene(key, "must be finite");
    const float len = glm::length(vec3(c));
    if (!(len > 0.0f)) throw InvalidScene(key, "the normal (a, b, c) must not be zero");
    c /= len;  // so plane distances are in world units
  }
  clip_planes_ = std::move(clip_planes);
  versions_.geometry = next_version();
}

Box3 Scene::scene_box() const {
  Box3 box = volume().world_box();
  for (const MeshObject& m : meshes_) {
    const Box3 b = m.world_bounds();
    box.lower = glm::min(box.lower, b.lower);
    box.upper = glm::max(box.upper, b.upper);
  }
  return box;
}

void Scene::set_meshes(std::vector<MeshObject> meshes) {
  if (meshes.size() > std::size_t(kMaxMeshes)) {
    throw InvalidScene("meshes", fmt::format("at most {} meshes, got {}", kMaxMeshes, meshes.size()));
  }
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshObject& m = meshes[i];
    const std::string key = fmt::format("meshes[{}]", i);
    if (!m.mesh) throw InvalidScene(key, "has no triangles loaded");
    try {
      m.mesh->validate(key);
    } catch (const InvalidArgument& e) {
      throw InvalidScene(e.name(), e.what());
    }
    if (!finite3(m.scale) || m.scale.x == 0.0f || m.scale.y == 0.0f || m.scale.z == 0.0f) {
      throw InvalidScene(key + ".scale", "must be finite and non-zero");
    }
    if (!finite3(m.rotate_deg)) throw InvalidScene(key + ".rotate_deg", "must be finite");
    if (!finite3(m.translate)) throw InvalidScene(key + ".translate", "must be finite");
    const MeshMaterial& mat = m.material;
    if (!(mat.specular >= 0.0f && mat.specular <= 1.0f)) {
      throw InvalidScene(key + ".material.specular", "must be in [0, 1]");
    }
    if (!(mat.roughness > 0.0f && mat.roughness <= 1.0f)) {
      throw InvalidScene(key + ".material.roughness", "must be in (0, 1]");
    }
    if (const auto& t = mat.transport_color) {
      for (int c = 0; c < 3; ++c) {
        if (!((*t)[c] >= 0.0f && (*t)[c] <= 1.0f)) {
          throw InvalidScene(key + ".material.transport_color", "each channel must be in [0, 1]");
        }
      }
    }
    const DetailFunction& d = mat.detail;
    if (!(d.frequency > 0.0f) || !is_finite(d.frequency)) {
      throw InvalidScene(key + ".material.detail.frequency", "must be positive");
    }
    if (d.fractal.octaves < 1 || d.fractal.octaves > 16) {
      throw InvalidScene(key + ".material.detail.octaves", "must be in [1, 16]");
    }
    if (!(d.fractal.lacunarity >= 1.0f && d.fractal.lacunarity <= 8.0f)) {
      throw InvalidScene(key + ".material.detail.lacunarity", "must be in [1, 8]");
    }
    if (!(d.fractal.gain >= 0.0f && d.fractal.gain <= 1.0f)) {
      throw InvalidScene(key + ".material.detail.gain", "must be in [0, 1]");
    }
    if (!is_finite(d.fractal.offset) || !is_finite(d.fractal.time) || !is_finite(d.value)) {
      throw InvalidScene(key + ".material.detail", "offset, time and value must be finite");
    }
    if (d.type == DetailType::Texture && !d.texture) {
      throw InvalidScene(key + ".material.detail.texture", "the texture volume is not loaded");
    }
  }
  meshes_ = std::move(meshes);
  versions_.meshes = next_version();
}

void Scene::set_render(RenderSettings render) {
  render.validate();
  render_ = std::move(render);
  versions_.render = next_version();
}

vec2 Scene::tf_value_range() const {
  const ValueRange r = volume().value_range();
  return transfer_function_.resolve_range(vec2(r.min, r.max));
}

float Scene::unit_length() const {
  return transfer_function_.unit_length().value_or(min_component(volume().spacing()));
}

const TransferFunction& Scene::shadow_tf() const {
  return shadow_transfer_function_ ? *shadow_transfer_function_ : transfer_function_;
}

vec2 Scene::shadow_tf_value_range() const {
  const ValueRange r = volume().value_range();
  return shadow_tf().resolve_range(vec2(r.min, r.max));
}

float Scene::shadow_unit_length() const {
  return shadow_tf().unit_length().value_or(min_component(volume().spacing()));
}

float Scene::step_world() const { return render_.step * min_component(volume().spacing()); }

}  // namespace penumbra
