#pragma once
// The CPU half-angle slicer: per light, a sweep over the slices of
// slice_geometry.h with a 2D eye buffer (the image) and a 2D light buffer
// (light_cache_projection.h's mapping, light_buffer_size texels per side).
// Per slice, in parallel over buffer rows: opaque planes whose hit lies
// before this slice are shaded, the eye buffer takes the slice's samples lit
// by the light buffer, then the light buffer is attenuated by the slice and
// (with albedo > 0) its diffuse part blurred. Only the rows the slice's cut
// through the box projects to are visited; empty macrocells cost no sample.
// A row runs 8 or 16 pixels or texels at a time where the view can run as
// packets (half_angle_packets.cpp), one at a time otherwise: the same kernels
// (half_angle_kernels.h). Several lights: one sweep each, added up as in IPSVI.
#include "penumbra/render/image.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/scene/scene.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct HalfAngleSettings {
  int slices = 0;  // 0: one slab per ray step along the central viewing ray
  float cone_angle_deg = 20.0f;
  float albedo = 0.0f;
  int light_buffer_size = 0;  // texels per side; 0: max(image side, a texel per pixel at the volume)
};

class HalfAngleRenderer {
 public:
  void prepare(const Scene& scene, const HalfAngleSettings& settings);
  void render(const Scene& scene, Image& image, RenderStats* stats = nullptr);
  std::uint64_t aux_bytes() const;
  int last_slice_count() const { return last_slices_; }
  // How many times prepare() has built the light rays (light, data or buffer
  // size changed).
  std::uint64_t rebuilds() const { return rebuilds_; }

 private:
  struct LightRays {
    LightCacheProjection projection;
    // Per texel: the light ray through its centre (SlicedRows' first six
    // fields, half_angle_kernels.h).
    std::vector<float> rays;
    std::size_t stride = 0;
  };

  SceneResources resources_;
  HalfAngleSettings settings_;
  std::vector<LightRays> lights_;
  int size_ = 0;
  std::uint64_t lights_version_ = 0, data_version_ = 0, rebuilds_ = 0;
  bool built_ = false;
  std::vector<vec4> light_, blur_;
  std::vector<vec4> sums_;
  // Per pixel, kept from frame to frame (a fresh allocation each frame cost
  // its page faults): the viewing rays and eye buffer (SlicedRows), the
  // plane each ray hits, the slice that reaches it, and whether it was shaded.
  std::vector<float> eye_;
  std::vector<int> eye_plane_, plane_slice_;
  std::vector<std::uint8_t> plane_done_;
  int last_slices_ = 0;
};

}  // namespace penumbra
