#include "penumbra/techniques/convolution/mesh_resources.h"

namespace penumbra {

void MeshResources::update(const Scene& scene) {
  if (!media_.update(scene)) return;
  ldi_current_ = false;
  corner_normals_.clear();
  // From the world positions and their (possibly swapped) winding: outward
  // in world space, no normal matrix needed.
  for (const TriangleMesh& w : media_.world_meshes()) corner_normals_.push_back(smooth_corner_normals(w));
}

void MeshResources::build_ldi(const CameraView& camera, int width, int height) {
  const auto same_camera = [](const CameraView& a, const CameraView& b) {
    return a.eye == b.eye && a.forward == b.forward && a.right == b.right && a.up == b.up &&
           a.half_height == b.half_height && a.orthographic == b.orthographic;
  };
  if (ldi_current_ && ldi_.width() == width && ldi_.height() == height && same_camera(ldi_camera_, camera)) return;
  ldi_current_ = false;  // stays false if the build throws
  std::vector<const TriangleMesh*> meshes;
  std::vector<const std::vector<vec3>*> normals;
  for (const TriangleMesh& m : media_.world_meshes()) meshes.push_back(&m);
  for (const std::vector<vec3>& n : corner_normals_) normals.push_back(&n);
  ldi_.build(meshes, normals, camera, width, height);
  ldi_camera_ = camera;
  ldi_current_ = true;
  ++ldi_builds_;
}

std::uint64_t MeshResources::bytes() const {
  std::uint64_t n = ldi_.bytes() + media_.bytes();
  for (const std::vector<vec3>& c : corner_normals_) n += c.size() * sizeof(vec3);
  return n;
}

}  // namespace penumbra
