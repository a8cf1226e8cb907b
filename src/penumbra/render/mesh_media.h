#pragma once
// The scene's closed meshes as media (scene/mesh.h, Patel et al. 2013):
// inside mesh m the extinction and colour are its material TF at its detail
// function. Every technique that draws meshes samples them through these
// views: convolution's slabs, the path tracer's tracking
// (techniques/pathtrace/mesh_tracking.h) and shadow-rays' marching
// (render/mesh_march.h). MeshMedia (host) keeps the meshes in world space,
// their detail and TF tables and, on request, one BVH per mesh for ray
// queries (scene/mesh_bvh.h).
#include "penumbra/render/march.h"
#include "penumbra/scene/detail_view.h"
#include "penumbra/scene/mesh_bvh.h"
#include "penumbra/scene/scene.h"

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
  // Light on its way to other samples attenuates with sigma_t * light_weight
  // per channel: 1 - the material's transport_color (1: grey, as the view).
  vec3 light_weight{1.0f};

  // The medium at a world point: (rgb, sigma_t per world unit).
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
  const MeshBvhView* shapes = nullptr;  // one per object once MeshMedia::build_shapes() ran, else null

  // The sum of the media of the meshes in `inside` (bit m: mesh m) at a
  // world point: extinction-weighted colour, summed extinction; and in
  // `light_sigma` the summed extinction of light per channel (light_weight).
  PENUMBRA_HD vec4 medium(std::uint32_t inside, vec3 world, vec3& light_sigma) const {
    vec3 weighted(0.0f);
    float sigma = 0.0f;
    light_sigma = vec3(0.0f);
    for (int m = 0; m < count; ++m) {
      if (!(inside & (1u << m))) continue;
      const vec4 c = objects[m].medium(world);
      weighted += c.a * vec3(c);
      sigma += c.a;
      light_sigma += c.a * objects[m].light_weight;
    }
    return sigma > 0.0f ? vec4(weighted / sigma, sigma) : vec4(0.0f);
  }
  PENUMBRA_HD vec4 medium(std::uint32_t inside, vec3 world) const {
    vec3 unused;
    return medium(inside, world, unused);
  }
};

// Crossings kept per mesh and ray; a ray crossing one mesh more often keeps
// 64 of them (those the BVH visits first) and may see its inside wrongly.
inline constexpr int kMeshCrossings = 64;

// The crossings of `ray` with mesh m beyond t = 0, sorted, into t[0..n) (n
// returned); `inside` says whether the ray starts inside (an odd number of
// crossings to infinity).
PENUMBRA_HD inline int sorted_crossings(const MeshesView& meshes, int m, const Ray& ray, float* t, bool& inside) {
  const int total = meshes.shapes[m].crossings(ray, 0.0f, kInfinity, t, kMeshCrossings);
  const int n = total < kMeshCrossings ? total : kMeshCrossings;
  for (int i = 1; i < n; ++i) {  // insertion sort: n is small
    const float v = t[i];
    int j = i - 1;
    for (; j >= 0 && t[j] > v; --j) t[j + 1] = t[j];
    t[j + 1] = v;
  }
  inside = (total % 2) == 1;
  return n;
}

// The parts of `ray` within [0, t_max] inside mesh m: calls f(a, b) for
// each, nearest first, until f returns false.
template <class F>
PENUMBRA_HD void for_each_inside_part(const MeshesView& meshes, int m, const Ray& ray, float t_max, const F& f) {
  float t[kMeshCrossings];
  bool inside = false;
  const int n = sorted_crossings(meshes, m, ray, t, inside);
  float from = 0.0f;
  for (int i = 0; i <= n; ++i) {
    const float to = i < n ? t[i] : kInfinity;
    if (inside && from < t_max && !f(from, glm::min(to, t_max))) return;
    if (to >= t_max) return;
    inside = !inside;
    from = to;
  }
}

// The meshes' optical depth for light along [0, t_max] of `ray`, per
// channel (sigma_t * light_weight), each part inside a mesh integrated by
// the midpoint rule over equal steps of at most `step` (exact for
// homogeneous media, whatever the step: the parts' ends are the exact
// crossings). Stops adding once every channel passes `max_depth`.
PENUMBRA_HD inline vec3 mesh_optical_depth(const MeshesView& meshes, const Ray& ray, float t_max, float step,
                                           float max_depth, std::uint64_t& lookups) {
  vec3 depth(0.0f);
  const auto below = [&] { return glm::min(depth.x, glm::min(depth.y, depth.z)) < max_depth; };
  for (int m = 0; m < meshes.count && below(); ++m) {
    const MeshMaterialView& mat = meshes.objects[m];
    if (!(mat.sigma_max > 0.0f)) continue;
    for_each_inside_part(meshes, m, ray, t_max, [&](float a, float b) {
      const int n = glm::max(1, int(glm::ceil((b - a) / step)));
      const float h = (b - a) / float(n);
      for (int i = 0; i < n && below(); ++i) {
        depth += (mat.medium(ray.at(a + (float(i) + 0.5f) * h)).a * h) * mat.light_weight;
        ++lookups;
      }
      return below();
    });
  }
  return depth;
}

// exp(-density_scale * optical depth) through the meshes per channel (0 past
// kMaxOpticalDepth, as march_transmittance).
PENUMBRA_HD inline vec3 mesh_transmittance(const MeshesView& meshes, const Ray& ray, float t_max, float step,
                                           float density_scale, std::uint64_t& lookups) {
  if (meshes.count == 0 || density_scale <= 0.0f) return vec3(1.0f);
  const vec3 depth = density_scale * mesh_optical_depth(meshes, ray, t_max, step, kMaxOpticalDepth / density_scale,
                                                        lookups);
  vec3 t;
  for (int c = 0; c < 3; ++c) t[c] = depth[c] < kMaxOpticalDepth ? exp_nonpositive(-depth[c]) : 0.0f;
  return t;
}

// The same for the W rays of a packet whose lane is on (1 elsewhere): the
// BVH walk is per ray, so lane by lane.
template <class L>
PENUMBRA_HD typename L::Vec3 mesh_transmittance(const MeshesView& meshes, const Ray* rays, const float* t_max,
                                                float step, float density_scale, typename L::Mask active,
                                                std::uint64_t& lookups) {
  vec3 out[L::kWidth];
  const std::uint32_t on = L::bits(active);
  for (int i = 0; i < L::kWidth; ++i) {
    out[i] = (on >> i) & 1u ? mesh_transmittance(meshes, rays[i], t_max[i], step, density_scale, lookups) : vec3(1.0f);
  }
  return pack_lanes<L>(out);
}

class MeshMedia {
 public:
  // Rebuilds the world meshes, detail and TF tables when the scene's meshes
  // (or the TF unit length they default to) changed; returns whether it did.
  bool update(const Scene& scene);
  // The BVHs of the world meshes (kept while the meshes do not change).
  void build_shapes();
  // How often the world meshes were rebuilt.
  int builds() const { return builds_; }

  bool empty() const { return objects_.empty(); }
  MeshesView view() const;
  const std::vector<TriangleMesh>& world_meshes() const { return world_; }
  Box3 world_bounds() const { return bounds_; }
  // The distance that samples every mesh's detail (Patel et al. 2013,
  // section 7: from a texture's dimensions, and for procedural detail from
  // its frequency): half the world size of the finest lattice cell (the
  // highest octave's) or of a texel, the smallest over the meshes; +inf when
  // no mesh has detail that varies (constant detail, or no meshes).
  float detail_sampling_distance() const { return detail_distance_; }
  // The meshes' largest extinction (0 without meshes).
  float sigma_max() const;
  // Whether any mesh's material has a transport colour (light attenuates
  // per channel).
  bool chromatic() const { return chromatic_; }
  // The step that samples the meshes' media (shadow-rays): at most the
  // render step and the detail's sampling distance, at least min_step().
  float sampling_step(float render_step) const;
  // 1/4096 of the meshes' bounding diagonal (0 without meshes).
  float min_step() const;
  std::uint64_t bytes() const;

 private:
  std::uint64_t version_ = 0;
  float unit_length_ = 0.0f;
  std::vector<TriangleMesh> world_;
  std::vector<std::unique_ptr<DetailResources>> details_;
  std::vector<TransferFunctionTable> tfs_;
  std::vector<std::unique_ptr<DetailResources>> color_details_;  // null where a mesh has no colour detail
  std::vector<std::unique_ptr<TransferFunctionTable>> color_tfs_;
  std::vector<MeshMaterialView> objects_;
  Box3 bounds_{vec3(kInfinity), vec3(-kInfinity)};
  float detail_distance_ = kInfinity;
  bool chromatic_ = false;
  std::vector<MeshBvh> bvhs_;
  std::vector<MeshBvhView> shapes_;
  int builds_ = 0;
};

}  // namespace penumbra
