#pragma once
// What the slab renderer needs of the scene's meshes: the meshes moved to
// world space with their smooth shading normals (smooth_corner_normals), each
// mesh's detail function and material TF as plain views (rebuilt when the
// meshes change), and the layered depth image (rebuilt when the camera, the
// image size or the meshes change); for ray queries (the path tracer), a BVH
// per mesh, built on first request after the meshes change.
#include "penumbra/scene/detail_view.h"
#include "penumbra/scene/mesh_bvh.h"
#include "penumbra/scene/scene.h"
#include "penumbra/techniques/convolution/layered_depth_image.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra {

struct MeshMaterialView {
  DetailView detail;         // of object-space positions
  TransferFunctionView tf;   // detail value -> (rgb, sigma_t per world unit)
  bool colored = false;      // the colour comes from color_detail through color_tf instead
  DetailView color_detail;
  TransferFunctionView color_tf;
  mat4 world_to_object{1.0f};
  float specular = 0.0f;     // F0
  float roughness = 0.3f;    // GGX alpha
  float sigma_max = 0.0f;    // the TF's largest extinction: a majorant of the medium

  // The medium at a world point: (rgb, sigma_t per world unit), what
  // convolution's slabs and the path tracer's mesh media both sample.
  PENUMBRA_HD vec4 medium(vec3 world) const {
    const vec3 object(world_to_object * vec4(world, 1.0f));
    vec4 c = tf.lookup(detail(object));
    if (colored) {
      const vec4 colour = color_tf.lookup(color_detail(object));
      c = vec4(vec3(colour), c.a);
    }
    return c;
  }
};

struct MeshesView {
  const MeshMaterialView* objects = nullptr;
  int count = 0;
  LdiView ldi{};
  const MeshBvhView* shapes = nullptr;  // one per object once build_shapes() ran, else null
};

class MeshResources {
 public:
  // Rebuilds everything but the LDI when the scene's meshes (or the TF unit
  // length they default to) changed.
  void update(const Scene& scene);
  // The layered depth image for this camera and size; kept while neither
  // they nor the meshes change (a TF or light edit does not rebuild it).
  void build_ldi(const CameraView& camera, int width, int height);
  // The BVHs of the world meshes (kept while the meshes do not change).
  void build_shapes();
  // How often the meshes' world copies and the LDI were rebuilt.
  int builds() const { return mesh_builds_ + ldi_builds_; }

  bool empty() const { return objects_.empty(); }
  MeshesView view() const;
  Box3 world_bounds() const { return bounds_; }
  // The slab distance that samples every mesh's detail (Patel et al. 2013,
  // section 7: from a texture's dimensions, and for procedural detail from
  // its frequency): half the world size of the finest lattice cell (the
  // highest octave's) or of a texel, the smallest over the meshes; +inf when
  // no mesh has detail that varies (constant detail, or no meshes).
  float detail_slab_distance() const { return detail_distance_; }
  std::uint64_t bytes() const;

 private:
  std::uint64_t version_ = 0;
  float unit_length_ = 0.0f;
  std::vector<TriangleMesh> world_;
  std::vector<std::vector<vec3>> corner_normals_;  // per world mesh: smooth shading normals for the LDI
  std::vector<std::unique_ptr<DetailResources>> details_;
  std::vector<TransferFunctionTable> tfs_;
  std::vector<std::unique_ptr<DetailResources>> color_details_;  // null where a mesh has no colour detail
  std::vector<std::unique_ptr<TransferFunctionTable>> color_tfs_;
  std::vector<MeshMaterialView> objects_;
  Box3 bounds_{vec3(kInfinity), vec3(-kInfinity)};
  float detail_distance_ = kInfinity;
  std::vector<MeshBvh> bvhs_;
  std::vector<MeshBvhView> shapes_;
  LayeredDepthImage ldi_;
  CameraView ldi_camera_;
  bool ldi_current_ = false;
  int ldi_builds_ = 0;
  int mesh_builds_ = 0;
};

}  // namespace penumbra
