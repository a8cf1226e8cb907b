#pragma once
// What the slab renderer needs of the scene's meshes: the meshes as media
// (render/mesh_media.h: world space, detail functions and material TFs as
// plain views, rebuilt when the meshes change), their smooth shading normals
// (smooth_corner_normals) and the layered depth image (rebuilt when the
// camera, the image size or the meshes change).
#include "penumbra/render/mesh_media.h"
#include "penumbra/scene/scene.h"
#include "penumbra/techniques/convolution/layered_depth_image.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// The meshes' media and their layered depth image.
struct SlabMeshesView : MeshesView {
  LdiView ldi{};
};

class MeshResources {
 public:
  // Rebuilds everything but the LDI when the scene's meshes (or the TF unit
  // length they default to) changed.
  void update(const Scene& scene);
  // The layered depth image for this camera and size; kept while neither
  // they nor the meshes change (a TF or light edit does not rebuild it).
  void build_ldi(const CameraView& camera, int width, int height);
  // How often the meshes' world copies and the LDI were rebuilt.
  int builds() const { return media_.builds() + ldi_builds_; }

  bool empty() const { return media_.empty(); }
  // Whether light attenuates per colour channel (a transport colour).
  bool chromatic() const { return media_.chromatic(); }
  SlabMeshesView view() const { return SlabMeshesView{media_.view(), ldi_.view()}; }
  Box3 world_bounds() const { return media_.world_bounds(); }
  // The slab distance that samples every mesh's detail
  // (MeshMedia::detail_sampling_distance).
  float detail_slab_distance() const { return media_.detail_sampling_distance(); }
  std::uint64_t bytes() const;

 private:
  MeshMedia media_;
  std::vector<std::vector<vec3>> corner_normals_;  // per world mesh: smooth shading normals for the LDI
  LayeredDepthImage ldi_;
  CameraView ldi_camera_;
  bool ldi_current_ = false;
  int ldi_builds_ = 0;
};

}  // namespace penumbra
