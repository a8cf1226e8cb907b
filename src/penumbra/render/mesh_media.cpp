#include "penumbra/render/mesh_media.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// The values a detail function takes, for a TF range of "data".
vec2 natural_range(const DetailFunction& d) {
  switch (d.type) {
    case DetailType::Constant: return vec2(0.0f, 1.0f);
    case DetailType::Noise:
    case DetailType::Fbm: return vec2(-1.0f, 1.0f);
    case DetailType::Ridged: return vec2(0.0f, 2.0f);
    case DetailType::Texture:
      if (d.texture) return vec2(d.texture->value_range().min, d.texture->value_range().max);
      return vec2(0.0f, 1.0f);
  }
  return vec2(0.0f, 1.0f);
}

// Half the world size of the finest feature of mesh m's detail: a lattice
// cell of its highest octave, or a texel of its texture stretched over the
// mesh's object-space bounds; +inf for constant detail. Along each object
// axis the world length is the axis's column of object_to_world; the
// smallest axis counts.
float feature_sampling_distance(const MeshObject& m, const DetailFunction& d) {
  const mat3 to_world(m.object_to_world());
  const vec3 axis_scale(glm::length(to_world[0]), glm::length(to_world[1]), glm::length(to_world[2]));
  vec3 feature(kInfinity);  // object-space size of the finest feature per axis
  switch (d.type) {
    case DetailType::Constant: return kInfinity;
    case DetailType::Noise: feature = vec3(1.0f / d.frequency); break;
    case DetailType::Fbm:
    case DetailType::Ridged: {
      const int octaves = glm::max(d.fractal.octaves, 1);
      const float finest = d.frequency * std::pow(glm::max(d.fractal.lacunarity, 1.0f), float(octaves - 1));
      feature = vec3(1.0f / finest);
      break;
    }
    case DetailType::Texture: {
      if (!d.texture) return kInfinity;
      // The texel centres span the bounds, first and last on them (detail_view.h).
      feature = m.mesh->bounds().extent() / vec3(glm::max(d.texture->dims() - 1, ivec3(1)));
      break;
    }
  }
  const vec3 world = feature * axis_scale;
  const float smallest = glm::min(world.x, glm::min(world.y, world.z));
  return smallest > 0.0f ? 0.5f * smallest : kInfinity;
}

}  // namespace

bool MeshMedia::update(const Scene& scene) {
  const float unit = scene.unit_length();
  if (scene.versions().meshes == version_ && unit == unit_length_) return false;
  version_ = scene.versions().meshes;
  bvhs_.clear();
  shapes_.clear();
  if (!scene.meshes().empty()) ++builds_;
  unit_length_ = unit;
  const std::vector<MeshObject>& meshes = scene.meshes();
  world_.assign(meshes.size(), TriangleMesh{});
  details_.clear();
  tfs_.clear();
  color_details_.clear();
  color_tfs_.clear();
  objects_.clear();
  chromatic_ = std::any_of(meshes.begin(), meshes.end(),
                           [](const MeshObject& m) { return m.material.transport_color.has_value(); });
  bounds_ = Box3{vec3(kInfinity), vec3(-kInfinity)};
  detail_distance_ = kInfinity;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshObject& m = meshes[i];
    detail_distance_ = glm::min(detail_distance_, feature_sampling_distance(m, m.material.detail));
    if (m.material.has_color_detail) {
      detail_distance_ = glm::min(detail_distance_, feature_sampling_distance(m, m.material.color_detail));
    }
    const mat4 to_world = m.object_to_world();
    TriangleMesh& w = world_[i];
    w.triangles = m.mesh->triangles;
    // A mirroring scale turns the winding inside out; swap two corners so
    // normals still point outward.
    if (glm::determinant(mat3(to_world)) < 0.0f) {
      for (glm::uvec3& t : w.triangles) std::swap(t.y, t.z);
    }
    w.positions.reserve(m.mesh->positions.size());
    for (const vec3& p : m.mesh->positions) w.positions.emplace_back(to_world * vec4(p, 1.0f));
    const Box3 b = w.bounds();
    bounds_.lower = glm::min(bounds_.lower, b.lower);
    bounds_.upper = glm::max(bounds_.upper, b.upper);

    const MeshMaterial& mat = m.material;
    details_.push_back(std::make_unique<DetailResources>(mat.detail, m.mesh->bounds()));
    const float tf_unit = mat.tf.unit_length().value_or(unit);
    tfs_.emplace_back(mat.tf, mat.tf.resolve_range(natural_range(mat.detail)), tf_unit);
    if (mat.has_color_detail) {
      color_details_.push_back(std::make_unique<DetailResources>(mat.color_detail, m.mesh->bounds()));
      color_tfs_.push_back(std::make_unique<TransferFunctionTable>(
          mat.color_tf, mat.color_tf.resolve_range(natural_range(mat.color_detail)), tf_unit));
    } else {
      color_details_.push_back(nullptr);
      color_tfs_.push_back(nullptr);
    }
  }
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    MeshMaterialView v;
    v.detail = details_[i]->view();
    v.tf = tfs_[i].view();
    if (color_details_[i]) {
      v.colored = true;
      v.color_detail = color_details_[i]->view();
      v.color_tf = color_tfs_[i]->view();
    }
    v.world_to_object = glm::inverse(meshes[i].object_to_world());
    v.specular = meshes[i].material.specular;
    v.roughness = meshes[i].material.roughness;
    if (const auto& t = meshes[i].material.transport_color) v.light_weight = 1.0f - *t;
    for (int e = 0; e < v.tf.size; ++e) v.sigma_max = glm::max(v.sigma_max, v.tf.sigma[e]);
    objects_.push_back(v);
  }
  return true;
}

void MeshMedia::build_shapes() {
  if (!shapes_.empty() || world_.empty()) return;
  for (const TriangleMesh& m : world_) bvhs_.emplace_back(m);
  for (const MeshBvh& b : bvhs_) shapes_.push_back(b.view());
}

MeshesView MeshMedia::view() const {
  return MeshesView{objects_.data(), int(objects_.size()), shapes_.empty() ? nullptr : shapes_.data()};
}

float MeshMedia::sigma_max() const {
  float s = 0.0f;
  for (const MeshMaterialView& m : objects_) s = glm::max(s, m.sigma_max);
  return s;
}

float MeshMedia::sampling_step(float render_step) const {
  return glm::max(glm::min(render_step, detail_distance_), min_step());
}

float MeshMedia::min_step() const {
  return empty() ? 0.0f : glm::length(bounds_.upper - bounds_.lower) / 4096.0f;
}

std::uint64_t MeshMedia::bytes() const {
  std::uint64_t n = 0;
  for (const TriangleMesh& m : world_) n += m.positions.size() * sizeof(vec3) + m.triangles.size() * sizeof(glm::uvec3);
  for (const MeshBvh& b : bvhs_) n += b.bytes();
  return n;
}

}  // namespace penumbra
