#pragma once
// The CPU sweep driver of IPSVI (Sundén et al. 2011, sections 4.1 and 4.2).
// render_image's independent tiles cannot be used: a line may start only when
// the lines between it and the light are done. For every light, every zone of
// the sweep plan (sweep_plan.h) starts from a fresh illumination cache; its
// lines are taken `line_width` at a time, the rays of such a block run in
// parallel (parallel_for) reading the cache as the earlier blocks left it,
// and the block's writes are folded in before the next block starts: each
// written texel's own light ray (through its centre) is marched from the depth
// the texel held to the mean depth the block's rays wrote at. Writing the
// samples' light instead (the GPU version keeps the last sample's) resamples
// the cache sideways at every line, by up to a texel; over the ~100 lines a
// light ray crosses that blurs and shifts shadows by several texels (measured:
// spheres at 256^2 went from PSNR 29 to 49 dB against shadow-rays).
//
// Several lights: one sweep per light, each lit by its light only (ambient and
// background in the first), added up; the compositing weights are the same in
// every pass, so the sum is the image lit by all of them.
#include "penumbra/render/image.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/scene/scene.h"
#include "penumbra/techniques/ipsvi/early_termination.h"
#include "penumbra/techniques/ipsvi/illumination_cache.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"
#include "penumbra/techniques/ipsvi/light_model.h"
#include "penumbra/techniques/ipsvi/sweep_plan.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct IpsviSettings {
  float albedo = 0.0f;          // the paper's a: blend of forward multiple scattering
  float cone_angle_deg = 20.0f;
  int line_width = 1;
  int cache_size = 0;           // texels per side; 0: about one texel per pixel (ipsvi_cache_size)
  bool piecewise_integration = true;
  bool early_termination = false;
  float band_deg = 5.0f;        // zone-border blending (point lights)
  IpsviLightModel light_model = IpsviLightModel::Grey;  // light_model.h
  int segment_tape_limit = 0;   // light segments one ray records for packets (segment_tape.h; 0: all it can hold)
  bool operator==(const IpsviSettings&) const = default;
};

struct IpsviFrameCounts {
  std::uint64_t view_samples = 0;
  std::uint64_t light_samples = 0;    // piecewise-integration samples at the viewing-ray samples
  std::uint64_t write_samples = 0;    // piecewise-integration samples of cache writes
  std::uint64_t prepass_samples = 0;  // ERT extension pre-pass
  std::uint64_t exact_plane_rays = 0;  // plane hits on a shadow edge that marched their own light ray
  std::uint64_t packet_segments = 0;   // light segments (rays' and resolve's) marched as SIMD packets
  std::uint64_t blocks = 0;           // blocks of lines processed (synchronisation points)
};

// The illumination cache of each non-environment light, fitted to what the
// camera sees (cache_fit.h), all with the same size: the one `settings`
// asks for, or with 0 the largest whose texels are about a pixel wide at the
// visible part of the volume (for a light inside the box: at the box's
// half-diagonal from the light), 16 to three times the image's longer side,
// and at most 1.4 texels per image pixel in all: coarser texels where the
// visible region needs more. For a light inside the box an octahedral map,
// fitted to the directions toward the visible region, or of all directions
// where the light lies in that region, either at most 4 texels per image
// pixel.
// With several lights the others take the largest light's side, so their
// trimmed grids may hold more than that.
// Throws InvalidArgument naming cache_size for a size outside [16, 4096].
std::vector<LightCacheProjection> fit_ipsvi_caches(const Scene& scene, const IpsviSettings& settings);
// The size of those caches (16 without lights).
int ipsvi_cache_size(const Scene& scene, const IpsviSettings& settings);

class IpsviRenderer {
 public:
  void prepare(const Scene& scene, const IpsviSettings& settings);
  void render(const Scene& scene, Image& image, RenderStats* stats = nullptr);

  std::uint64_t aux_bytes() const;
  // Rebuilds: lights, data, clip planes, cache_size, the diffuse channel or
  // the light model changed. Refits (rebuilds included): the cache was fitted anew, as after
  // a camera move.
  std::uint64_t rebuilds() const { return rebuilds_; }
  std::uint64_t refits() const { return refits_; }
  const IpsviFrameCounts& last_counts() const { return counts_; }

 private:
  struct LightCache {
    Light light;
    LightCacheProjection projection;
    std::vector<vec2> initial;  // the cache at the start of each zone's sweep
  };

  SceneResources resources_;
  IpsviSettings settings_;
  std::vector<LightCache> lights_;
  IlluminationCache cache_;
  EarlyTermination early_;
  std::vector<vec4> sums_;
  std::vector<float> coverage_;
  int axis_hint_ = 1;
  std::uint64_t lights_version_ = 0, geometry_version_ = 0, data_version_ = 0;
  bool built_ = false;
  std::uint64_t rebuilds_ = 0, refits_ = 0;
  IpsviFrameCounts counts_;
};

}  // namespace penumbra
