#include "penumbra/techniques/convolution/slab_renderer.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/lighting.h"
#include "penumbra/render/microfacet.h"
#include "penumbra/techniques/convolution/carried_light.h"
#include "penumbra/techniques/convolution/light_propagation.h"
#include "penumbra/techniques/convolution/mesh_layers.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr int kMaxLights = 16;        // light buffers (environment lights have none)
constexpr int kMaxSceneLights = 64;   // per-pixel arrays are indexed by scene light
constexpr int kMaxSlabs = 16384;

struct PixelState {
  vec3 color{0.0f};
  float transmittance = 1.0f;
  vec3 ray_dir{0.0f, 0.0f, 1.0f};  // the pixel's viewing ray (along forward for an orthographic camera)
  float ray_cos = 1.0f;  // viewing ray . forward
  float z_in = 0.0f, z_out = -1.0f;  // depth interval inside box and clip planes
  float z_plane = kInfinity;
  int plane = -1;
  bool done = false;  // reached an opaque plane
  bool guard = false;  // in the guard band: attenuates light, is not shown
  float offset = 0.5f;  // where in its part of each slab the pixel samples: 0.5 (middle) or jittered
  float previous_value = std::numeric_limits<float>::quiet_NaN();  // preintegration: the last volume sample
  PixelLayers layers;
};

// Visibility from the light buffers at the current pixel (indexed by scene light).
struct BufferVisibility {
  const vec3* values;
  PENUMBRA_HD vec3 operator()(int light, vec3, const LightSample&) const { return values[light]; }
};

float box_depth(const Box3& box, const CameraView& c, bool far_side) {
  float z = far_side ? -kInfinity : kInfinity;
  for (int i = 0; i < 8; ++i) {
    const vec3 p((i & 1) ? box.upper.x : box.lower.x, (i & 2) ? box.upper.y : box.lower.y,
                 (i & 4) ? box.upper.z : box.lower.z);
    const float d = glm::dot(p - c.eye, c.forward);
    z = far_side ? glm::max(z, d) : glm::min(z, d);
  }
  return z;
}

// The light a segment scatters toward the viewer, relative to the midpoint
// sample's alpha * incoming light: the segment has optical depth a along the
// viewing ray and its medium takes b of the light across it, in proportion to
// depth (the slab model: light enters through the slab's front face). The
// in-scattered fraction is int_0^1 a e^{-a u} e^{-b u} du
//   = a / (a + b) (1 - e^{-(a + b)}),
// so the factor is that over 1 - e^{-a}. It is exact for a homogeneous slab
// whatever its optical thickness (the midpoint rule e^{-b/2} is its limit for
// thin segments, and bands a surface slabs cut obliquely when a is large).
PENUMBRA_HD inline float segment_light_factor(float a, float b) {
  if (b <= 0.0f) return 1.0f;
  const float ab = a + b;
  const float along = ab > 1e-4f ? -std::expm1(-ab) / ab : 1.0f - 0.5f * ab;   // (1 - e^{-(a+b)}) / (a + b)
  const float alpha = a > 1e-4f ? -std::expm1(-a) / a : 1.0f - 0.5f * a;       // (1 - e^{-a}) / a
  return along / alpha;
}

// The same per colour channel of b (one evaluation when the light is grey).
inline vec3 segment_light_factor(float a, vec3 b) {
  if (b.x == b.y && b.y == b.z) return vec3(segment_light_factor(a, b.x));
  return vec3(segment_light_factor(a, b.x), segment_light_factor(a, b.y), segment_light_factor(a, b.z));
}

}  // namespace

bool SlabRenderer::volume_has_extinction(const RenderView& view, const RenderView& shadow) const {
  const std::size_t cells = resources_.majorants().majorant.size();
  const auto any_extinction = [cells](const float* m) {
    return m && std::any_of(m, m + cells, [](float x) { return x > 0.0f; });
  };
  return any_extinction(view.majorants) || any_extinction(shadow.majorants);
}

// The slab distance when none is set (Patel et al. 2013, section 7): the
// render step where the volume has any extinction (for the viewer or, with
// a shadow TF, for the light), and no more than the
// meshes' detail asks for (MeshResources::detail_slab_distance). A scene
// whose volume is empty takes the detail's distance alone; with neither,
// the render step. At most kAutomaticSlabs slabs through the scene's depth.
float SlabRenderer::automatic_slab_distance(const RenderView& view, const RenderView& shadow, float depth,
                                            const std::vector<GaussianLight>& lights) const {
  float e = volume_has_extinction(view, shadow) ? view.step : kInfinity;
  e = glm::min(e, meshes_.detail_slab_distance());
  if (!(e < kInfinity)) e = view.step;
  // A light's path crosses a slab sideways by e |mu| (mu = tan of its angle to
  // the view), and the slab loop treats that crossing as one step down a
  // column followed by one sideways move; its error grows with the drift (on
  // a mesh sphere, rings where surfaces cut the slabs; in a volume, shadows
  // displaced). Thinner slabs also cost accuracy in volumes (the grid's
  // reads smooth the medium about a pixel out of a lit face, a bias that the
  // slabs' own error cancels near the step: docs/convolution.md, "Why
  // thinner slabs darken a lit face"), so e stays at the step unless a light
  // drifts more than a voxel a slab.
  const float voxel = view.volume.min_spacing();
  float drift_e = e;
  for (const GaussianLight& l : lights) {
    const float tan = glm::length(l.mu);
    if (tan * drift_e > voxel) drift_e = voxel / tan;
  }
  e = glm::max(drift_e, e / kMaxDriftRefinement);
  return glm::max(e, depth / float(kAutomaticSlabs));
}

void SlabRenderer::prepare(const Scene& scene, const SlabSettings& settings) {
  resources_.update(scene, scene.material().shading == Shading::Phong);
  meshes_.update(scene);
  settings_ = settings;
}

void SlabRenderer::render(const Scene& scene, Image& image, RenderStats* stats) {
  RenderView view = resources_.view(scene);
  const RenderView shadow = resources_.shadow_view(scene);
  const int image_width = view.width, image_height = view.height;
  if (image.width() != image_width || image.height() != image_height) image = Image(image_width, image_height);
  const CameraView& cam = view.camera;  // widened by the guard band below
  Box3 box = view.box;
  if (!meshes_.empty()) {
    box.lower = glm::min(box.lower, meshes_.world_bounds().lower);
    box.upper = glm::max(box.upper, meshes_.world_bounds().upper);
  }
  const vec3 center = box.center();

  // One Gaussian light and kernel per non-environment light.
  std::vector<int> slot_of(scene.lights().size(), -1);
  std::vector<GaussianLight> lights;
  for (std::size_t i = 0; i < scene.lights().size(); ++i) {
    const Light& l = scene.lights()[i];
    if (l.type == LightType::Environment) continue;
    slot_of[i] = int(lights.size());
    lights.push_back(gaussian_light(l, cam, center, settings_.light));
  }
  if (lights.size() > std::size_t(kMaxLights) || scene.lights().size() > std::size_t(kMaxSceneLights)) {
    throw InvalidScene("lights", "convolution supports at most 16 lights besides environment lights (64 in all)");
  }
  const int light_count = int(lights.size());

  const float voxel = view.volume.min_spacing();
  float z_front = box_depth(box, cam, false);
  float z_back = box_depth(box, cam, true);
  const float z_box_back = z_back;  // no volume sample or mesh lies beyond
  if (!cam.orthographic) z_front = glm::max(z_front, 1e-4f);
  const float box_extent = glm::max(z_back - z_front, 0.0f);
  const float e = settings_.slab_distance_voxels > 0.0f ? settings_.slab_distance_voxels * voxel
                                                        : automatic_slab_distance(view, shadow, box_extent, lights);
  const float d1 = settings_.optimal_distance_voxels > 0.0f ? settings_.optimal_distance_voxels * voxel
                                                            : glm::max(0.25f * box_extent, e);

  // A guard band around the image (issue 23): the slabs are swept over a
  // frame `guard` pixels wider on every side (the same pixel size and
  // centre: half_height grows with the pixel count), so occluders just
  // outside the view still shadow what it shows, instead of the light
  // buffers' clamp-to-edge repeating the border pixels (a false streak where
  // a mesh touches the border). Its width is what the light can travel
  // across the scene's depth, the mean drift |mu| D plus 3 standard
  // deviations of its accumulated blur sqrt(d1 sigma^2 D), at the pixel size
  // of the nearest depth, plus 2 texels of interpolation support; capped at
  // an eighth of the image per side (at most 1.56 x the pixels). Guard pixels
  // only attenuate light: they are not shaded.
  // The meshes' layered depth image covers the widest band (the cap) whatever
  // the lights, so moving a light does not rebuild it.
  const int max_guard = settings_.guard_band ? glm::max(2, glm::max(image_width, image_height) / 8) : 0;
  int guard = 0;
  if (light_count > 0 && settings_.guard_band) {
    const float near_depth = cam.orthographic ? z_front : glm::max(z_front, 1e-3f);
    const float texels_near = slab_mapping(SlabFrame{cam, image_width, image_height, 0.0f}, near_depth).pixels_per_unit;
    float footprint = 0.0f;
    for (const GaussianLight& g : lights) {
      const float var = principal_axes(g.covariance).var_x;
      footprint = glm::max(footprint, glm::length(g.mu) * box_extent + 3.0f * std::sqrt(d1 * var * box_extent));
    }
    const float wanted = std::ceil(glm::min(footprint * texels_near, 1e6f)) + 2.0f;
    guard = int(glm::min(wanted, float(max_guard)));
  }
  view.width = image_width + 2 * guard;
  view.height = image_height + 2 * guard;
  if (guard > 0) view.camera.half_height *= float(view.height) / float(image_height);
  const int width = view.width, height = view.height;

  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  // Light buffers hold one grey transmittance per texel, or one per colour
  // channel when a mesh's transport colour attenuates light chromatically
  // (Patel et al. 2013, Fig. 7e; DESIGN-NOTES).
  const int channels = meshes_.chromatic() ? 3 : 1;
  check_memory_budget("convolution buffers",
                      checked_product({pixels, 2 * std::uint64_t(light_count) * std::uint64_t(channels) * sizeof(float) +
                                                   sizeof(PixelState)}));
  const int ldi_shift = max_guard - guard;  // LDI pixel of this frame's pixel (0, 0)
  if (!meshes_.empty()) {
    CameraView ldi_camera = cam;
    if (max_guard > guard) ldi_camera.half_height *= float(image_height + 2 * max_guard) / float(height);
    meshes_.build_ldi(ldi_camera, image_width + 2 * max_guard, image_height + 2 * max_guard);
  }
  const SlabMeshesView meshes = meshes_.view();
  const bool has_meshes = meshes.count > 0;
  if (settings_.preintegrated) preintegration_.update(view.tf, e);
  const PreintegrationView preintegrated = preintegration_.view();
  const bool use_preintegration = settings_.preintegrated;

  // Per pixel: its ray, the volume's depth interval, the nearest plane and the
  // meshes' starting parity.
  std::vector<PixelState> px(pixels);
  const float diagonal = glm::length(box.upper - box.lower);
  parallel_for(0, height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < width; ++x) {
        PixelState& p = px[std::size_t(x) + std::size_t(width) * std::size_t(y)];
        const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, width, height);
        p.ray_dir = ray.direction;
        p.ray_cos = glm::dot(ray.direction, cam.forward);
        p.guard = x < guard || y < guard || x >= width - guard || y >= height - guard;
        if (settings_.jitter) p.offset = pixel_hash_offset(x - guard, int(y) - guard);
        float t_plane = kInfinity;
        p.plane = nearest_plane(view, ray, kInfinity, t_plane);
        if (p.plane >= 0) p.z_plane = t_plane * p.ray_cos;
        const Interval in = volume_interval(view, ray, 0.0f, t_plane);
        if (!in.empty()) {
          p.z_in = in.t0 * p.ray_cos;
          p.z_out = in.t1 * p.ray_cos;
        }
        if (has_meshes) p.layers = start_layers(meshes.ldi, x + ldi_shift, int(y) + ldi_shift);
      }
    }
  });
  // Slabs continue to the farthest plane hit, at most one box diagonal beyond the box.
  const float plane_limit = z_back + diagonal;
  for (const PixelState& p : px) {
    if (p.plane >= 0) z_back = glm::max(z_back, glm::min(p.z_plane, plane_limit));
  }
  const int slabs = int(std::ceil(glm::max(z_back - z_front, 0.0f) / e));
  if (slabs > kMaxSlabs) {
    throw InvalidArgument("slab_distance", "gives more than 16384 slabs through the scene; use a larger distance");
  }
  last_slabs_ = slabs;

  buffers_.assign(2 * pixels * std::size_t(light_count) * std::size_t(channels), 1.0f);
  std::vector<SlabKernelBuilder> kernels;
  std::vector<float> light_path;  // world length of light path per slab
  std::vector<vec3> light_travel;  // unit direction the light travels
  // Texels per world unit of lateral offset at the middle of the slabs (for
  // the kernels' interpolation correction, light_propagation.h).
  const float texels_per_unit =
      slab_mapping(SlabFrame{cam, width, height, e}, 0.5f * (z_front + z_back)).pixels_per_unit;
  for (int l = 0; l < light_count; ++l) {
    const GaussianLight& g = lights[std::size_t(l)];
    light_travel.push_back(glm::normalize(cam.forward + g.mu.x * cam.right + g.mu.y * cam.up));
    const std::uint64_t seed = mix_bits(settings_.seed * 0x2545f4914f6cdd1dULL + std::uint64_t(l));
    const vec2 mean = e * g.mu;
    const glm::mat2 covariance = interpolation_corrected_covariance(
        settings_.kernel, settings_.kernel_samples, mean, d1 * e * g.covariance, seed, texels_per_unit);
    kernels.emplace_back(settings_.kernel, settings_.kernel_samples, mean, covariance, seed);
    light_path.push_back(e / lights[std::size_t(l)].cos_view);
  }
  // Zero-variance lights are also carried along their rays across empty
  // space (carried_light.h), on grids that cover the frame down to the
  // smallest scale a perspective camera gives them over the slabs (z_first /
  // z_last, at least 0.9: below that they are re-sampled onto the pixel grid,
  // which keeps a grid at 1.23x the frame's texels).
  std::vector<char> carried(static_cast<std::size_t>(light_count), 0);
  for (int l = 0; l < light_count; ++l) {
    carried[std::size_t(l)] = settings_.carried_light && kernels[std::size_t(l)].sample_count() == 1;
  }
  const bool any_carried = std::find(carried.begin(), carried.end(), 1) != carried.end();
  float min_scale = 1.0f;
  if (!cam.orthographic && slabs > 1) {
    const float z_first = z_front + 0.5f * e, z_last = z_front + (float(slabs) - 0.5f) * e;
    min_scale = 0.98f * glm::clamp(z_first / z_last, 0.9f, 1.0f);
  }
  if (any_carried) {
    const CarriedGrid g = carried_grid(width, height, min_scale);
    const auto count = std::uint64_t(std::count(carried.begin(), carried.end(), 1));
    check_memory_budget("convolution carried light grids",
                        checked_product({std::uint64_t(g.width), std::uint64_t(g.height), 2 * count + 1,
                                         std::uint64_t(channels + 1) * sizeof(float)}));
  }
  // A texel must have travelled about a pixel clear of any medium before a
  // pixel takes its light (carried_light.h): that many slabs of the carried
  // lights' least sideways travel at the middle depth, at most 16.
  constexpr int kMaxClearSlabs = 16;
  float drift = kInfinity;  // pixels per slab
  const float middle_ppu = slab_mapping(SlabFrame{cam, width, height, e}, 0.5f * (z_front + z_back)).pixels_per_unit;
  for (int l = 0; l < light_count; ++l) {
    if (carried[std::size_t(l)]) drift = glm::min(drift, middle_ppu * e * glm::length(lights[std::size_t(l)].mu));
  }
  const int clear_slabs = drift * float(kMaxClearSlabs) > 1.0f ? int(std::ceil(1.0f / drift)) : kMaxClearSlabs;
  carried_.start(width, height, channels, min_scale, clear_slabs, carried);
  // Where the last slab has a medium and its extinction there (what the
  // carried grids test and are attenuated by).
  MediumMask medium;
  if (any_carried) medium.resize(width, height, channels);
  std::uint8_t* const has_medium = any_carried ? medium.flags() : nullptr;
  float* slab_extinction[3] = {nullptr, nullptr, nullptr};
  for (int c = 0; c < channels && any_carried; ++c) slab_extinction[c] = medium.extinction(c);
  const SlabFrame frame{cam, width, height, e};
  // A hard point light in front of the slabs diverges: the light reaching
  // lateral position X (camera right and up, world units) on the slab at depth
  // z came from L + r (X - L) on the slab before, r = (z - e - z_L) /
  // (z - z_L), L and z_L the light's lateral position and depth. On the pixel
  // grid that is the camera's slab map scaled by r, plus a single tap at the
  // constant lateral offset -(1 - r) L. Other lights (soft ones, a point
  // light beside or behind the slabs, and any light in a scene with meshes,
  // whose slanted paths take one drift per light) travel in one direction,
  // from the light toward the box's centre (gaussian_light.h).
  struct PointMap {
    bool on = false;
    vec2 lateral{0.0f};
    float depth = 0.0f;
  };
  std::vector<PointMap> point_maps(static_cast<std::size_t>(light_count));
  for (std::size_t i = 0; i < scene.lights().size(); ++i) {
    const int l = slot_of[i];
    const Light& light = scene.lights()[i];
    if (l < 0 || light.type != LightType::Point || has_meshes) continue;
    if (kernels[std::size_t(l)].sample_count() != 1) continue;
    const vec3 d = light.position - cam.eye;
    const float depth = glm::dot(d, cam.forward);
    if (!(depth < z_front - e)) continue;
    point_maps[std::size_t(l)] = PointMap{true, vec2(glm::dot(d, cam.right), glm::dot(d, cam.up)), depth};
  }
  vec2 point_taps[kMaxLights];
  const float unit_weight = 1.0f;
  // Light l's kernel for slab k (middle depth z), the map from its pixels to
  // the slab before, and the pixel offset w of the kernel's single tap.
  auto light_map = [&](int l, int k, float z, SlabKernel& kernel, SlabMapping& m, vec2& w) {
    kernel = kernels[std::size_t(l)].for_slab(k);
    m = slab_mapping(frame, z);
    const PointMap& pm = point_maps[std::size_t(l)];
    if (pm.on) {
      const float r = (z - e - pm.depth) / (z - pm.depth);
      m.scale *= r;
      point_taps[l] = -(1.0f - r) * pm.lateral;
      kernel.taps = &point_taps[l];
      kernel.weights = &unit_weight;
      kernel.count = 1;
      kernel.rotate_per_pixel = false;
      kernel.mean = point_taps[l];
    }
    const vec2 o = kernel.offset(0, 1.0f, 0.0f);
    w = m.pixels_per_unit * vec2(-o.x, o.y);
  };
  const float min_transmittance = 1.0f - view.ert_threshold;
  const bool separate_shadow_tf = scene.shadow_transfer_function().has_value();
  std::atomic<std::uint64_t> samples{0};
  int current = 0;  // which half of each light's pair holds the previous slab's light
  auto buffer = [&](int l, int half, int c = 0) {
    return buffers_.data() + std::size_t((2 * l + half) * channels + c) * pixels;
  };
  // The light of buffer pair l's half at texel i (grey or per channel).
  auto light_at = [&](int l, int half, std::size_t i) {
    return channels == 1 ? vec3(buffer(l, half)[i])
                         : vec3(buffer(l, half, 0)[i], buffer(l, half, 1)[i], buffer(l, half, 2)[i]);
  };
  const ScatteringLighting<BufferVisibility> volume_light{&view, {nullptr}, view.material.shading};
  const ScatteringLighting<BufferVisibility> mesh_light{&view, {nullptr}, Shading::Phase};

  auto shade_plane = [&](PixelState& p, int x, int y, const vec3* vis) {
    const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, width, height);
    const PlaneHit hit{ray.at(p.z_plane / p.ray_cos), p.plane, ray.direction};
    ScatteringLighting<BufferVisibility> lighting = volume_light;
    lighting.visibility.values = vis;
    p.color += p.transmittance * lighting.plane(hit);
    p.transmittance = 0.0f;
    p.done = true;
  };

  // The empty tail. Slabs behind the box of the volume and the meshes hold
  // no medium (unless a ray ends inside a mesh, an open one),
  // and only the pixels whose plane a slab hits read their light. Once
  // every carried texel has been clear of a medium for min_age slabs,
  // propagate gives every pixel the carried light. So, from there to the
  // last slab but one, a slab steps the carried grids (a soft light's
  // buffers are still convolved) and lights the pixels whose plane it hits,
  // one read each, instead of passing over every pixel (a floor far below
  // the volume: about half the slabs, docs/PERFORMANCE.md).
  bool ends_inside = false;
  if (has_meshes) {
    for (const PixelState& p : px) {
      std::uint32_t inside = p.layers.inside;
      for (std::uint32_t j = p.layers.next; j < p.layers.end; ++j) inside ^= 1u << meshes.ldi.fragments[j].object;
      ends_inside = ends_inside || inside != 0u;
    }
  }
  int tail_from = slabs;
  if (settings_.empty_tail && light_count > 0 && !ends_inside) {
    const int first_empty = int(std::ceil(glm::max(z_box_back - z_front, 0.0f) / e)) + 1;
    tail_from = glm::min(slabs, first_empty + (any_carried ? clear_slabs : 0) + 2);
  }
  // The tail's plane hits by slab (counting sort; filled when the tail starts).
  std::vector<std::uint32_t> tail_start, tail_pixels;
  auto slab_far_edge = [&](int k) { return (z_front + (float(k) + 0.5f) * e) + 0.5f * e; };  // the loop's z1
  auto start_tail = [&]() {
    const int count = slabs - tail_from;
    tail_start.assign(std::size_t(count) + 1, 0u);
    std::vector<int> slab_of(pixels, -1);
    for (std::size_t i = 0; i < pixels; ++i) {
      const PixelState& p = px[i];
      if (p.done || p.plane < 0) continue;
      int k = int(glm::clamp(std::floor((p.z_plane - z_front) / e), float(tail_from), float(slabs)));
      while (k > tail_from && p.z_plane < slab_far_edge(k - 1)) --k;
      while (k < slabs && !(p.z_plane < slab_far_edge(k))) ++k;
      if (k >= slabs - 1) continue;  // the last slab and beyond take the full pass
      slab_of[i] = k - tail_from;
      ++tail_start[std::size_t(k - tail_from) + 1];
    }
    for (int k = 0; k < count; ++k) tail_start[std::size_t(k) + 1] += tail_start[std::size_t(k)];
    tail_pixels.resize(tail_start.back());
    std::vector<std::uint32_t> fill(tail_start.begin(), tail_start.end() - 1);
    for (std::size_t i = 0; i < pixels; ++i) {
      if (slab_of[i] >= 0) tail_pixels[fill[std::size_t(slab_of[i])]++] = std::uint32_t(i);
    }
  };
  auto tail_slab = [&](int k, float z) {
    SlabMapping maps[kMaxLights];
    vec2 offsets[kMaxLights];
    const int next = 1 - current;
    for (int l = 0; l < light_count; ++l) {
      SlabKernel kernel;
      light_map(l, k, z, kernel, maps[l], offsets[l]);
      if (!carried[std::size_t(l)]) {
        for (int c = 0; c < channels; ++c) convolve_slab(frame, maps[l], kernel, buffer(l, current, c), buffer(l, next, c));
        continue;
      }
      carried_.advance(l, light_path[std::size_t(l)], medium, maps[l], offsets[l]);  // the mask is empty: the grid moves
    }
    current = next;  // a carried light's buffers are left stale: only the last slab reads them, where none is needed
    const std::size_t begin = tail_start[std::size_t(k - tail_from)], end = tail_start[std::size_t(k - tail_from) + 1];
    parallel_for(std::int64_t(begin), std::int64_t(end), [&](std::int64_t first, std::int64_t last) {
      vec3 vis[kMaxSceneLights];
      for (int i = 0; i < kMaxSceneLights; ++i) vis[i] = vec3(1.0f);
      for (std::int64_t j = first; j < last; ++j) {
        const std::size_t i = tail_pixels[std::size_t(j)];
        const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
        for (std::size_t s = 0; s < slot_of.size(); ++s) {
          const int l = slot_of[s];
          if (l < 0) continue;
          vis[s] = carried[std::size_t(l)]
                       ? carried_.read_clear(l, float(x) + 0.5f, float(y) + 0.5f, medium, maps[l], offsets[l])
                       : light_at(l, current, i);
        }
        shade_plane(px[i], x, y, vis);
      }
    }, 64);
  };
  last_tail_slabs_ = glm::max(slabs - 1 - tail_from, 0);

  // Light paths cross a slab slanted (slanted_paths.h): the pixel loop
  // leaves the buffers as they are, and after it every pixel's light is
  // attenuated along its path, slanted where it meets a mesh or the box.
  const bool slanted = light_count > 0 && has_meshes;
  std::vector<vec2> light_means;
  for (const GaussianLight& g : lights) light_means.push_back(e * g.mu);
  if (slanted) {
    // The volume's box counts where the volume has any extinction.
    std::vector<vec2> box_runs(pixels, vec2(1.0f, 0.0f));
    const bool volume = volume_has_extinction(view, shadow);
    for (std::size_t i = 0; i < pixels && volume; ++i) {
      const PixelState& p = px[i];
      if (p.z_in <= p.z_out) box_runs[i] = vec2(p.z_in, glm::min(p.z_out, p.z_plane));
    }
    slanted_.start(has_meshes ? &meshes.ldi : nullptr, ldi_shift, meshes_.builds(), box_runs, width, height);
  }
  std::vector<float*> planes(std::size_t(light_count) * std::size_t(channels));

  with_sampler(view.volume, [&](const auto& sampler) {
    using Sampler = std::decay_t<decltype(sampler)>;
    auto tf_lookup = [&](const TransferFunctionView& tf, float value) {
      return Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value);
    };
    // The volume's extinction toward the lights at world point q (per unit
    // path): none outside the box and the clip planes or in empty space.
    auto shadow_extinction = [&](vec3 q) {
      if (!view.box.contains(q) || !inside_clip_planes(q, view.clip_planes, view.clip_plane_count)) return 0.0f;
      const vec3 index = view.volume.index_from_world(q);
      return shadow.majorant_at(index) > 0.0f ? tf_lookup(shadow.tf, sampler(index)).a : 0.0f;
    };
    // Where the volume is the only medium, a carried texel that crosses it
    // samples it on its own ray (carried_light.h, advance_sampled): the
    // extinction at frame pixel coordinates q of the slab at depth `depth`.
    // With meshes the texels read the pixels' optical
    // depth, which holds the meshes' too; so do those of a point light in
    // front of the slabs, whose grid spreads to texels several pixels apart
    // (a sample per texel would place a sharp edge only to within half of
    // one: 0.97 px off in Convolution.PointLightShadowsDiverge, 0.04 px
    // reading the columns); and with preintegration, whose columns hold the
    // segments' optical depth rather than a sample's.
    auto texel_extinction = [&](float depth) {
      return [&, depth](vec2 q) { return shadow_extinction(slab_point(frame, q, depth)); };
    };
    const bool sampled_texels = !has_meshes && !use_preintegration;
    for (int k = 0; k < slabs; ++k) {
      const float z = z_front + (float(k) + 0.5f) * e;
      const float z0 = z - 0.5f * e, z1 = z + 0.5f * e;
      if (k >= tail_from && k < slabs - 1) {
        if (k == tail_from) start_tail();
        tail_slab(k, z);
        continue;
      }
      const int next = 1 - current;
      if (any_carried && k > 0) medium.build();
      if (slanted) slanted_.enter_slab(frame, z, light_means);
      for (int l = 0; l < light_count; ++l) {
        if (k == 0) continue;  // buffers start unoccluded
        SlabKernel kernel;
        SlabMapping m;
        vec2 w;
        light_map(l, k, z, kernel, m, w);
        if (carried[std::size_t(l)]) {
          if (sampled_texels && !point_maps[std::size_t(l)].on) {
            carried_.advance_sampled(l, light_path[std::size_t(l)], medium, m, w, texel_extinction(z - e));
          } else {
            carried_.advance(l, light_path[std::size_t(l)], medium, m, w);
          }
          carried_.propagate(l, frame, kernel, buffer(l, current), buffer(l, next), medium, m, w);
          continue;
        }
        for (int c = 0; c < channels; ++c) convolve_slab(frame, m, kernel, buffer(l, current, c), buffer(l, next, c));
      }
      if (k > 0) current = next;
      parallel_for(0, height, [&](std::int64_t first, std::int64_t last) {
        std::uint64_t count = 0;
        vec3 incoming[kMaxSceneLights], vis[kMaxSceneLights];
        for (int i = 0; i < kMaxSceneLights; ++i) incoming[i] = vis[i] = vec3(1.0f);
        for (std::int64_t y = first; y < last; ++y) {
          for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
            PixelState& p = px[i];
            if (has_medium) {
              has_medium[i] = 0;
              for (int c = 0; c < channels; ++c) slab_extinction[c][i] = 0.0f;
            }
            if (slanted) slanted_.clear(i, !p.done);
            if (p.done) continue;  // behind an opaque plane: nothing of this pixel is left to see or to shadow
            const bool plane_here = p.plane >= 0 && p.z_plane < z1;
            const bool shading = !p.guard && p.transmittance > min_transmittance;

            // The volume: the part of the slab inside the box and clip planes,
            // sampled at its middle or, with jitter, at the pixel's offset
            // along it (DESIGN-NOTES "Sampling": segments sum to the chord, so
            // a homogeneous medium integrates exactly either way). The
            // offset is the pixel's on every slab, as a ray caster's jitter
            // is the ray's: samples stay one slab apart along the ray.
            const float s0 = glm::max(z0, p.z_in), s1 = glm::min(z1, p.z_out);
            const float zs = s0 + p.offset * (s1 - s0);
            bool volume_here = s1 > s0 && !(p.plane >= 0 && p.z_plane <= zs);
            const bool crosses_box = volume_here;
            vec4 volume_sample(0.0f);  // (rgb, alpha) along the viewing ray
            float volume_shadow = 0.0f;  // optical depth toward the lights per unit light path
            float value = 0.0f;
            vec3 volume_pos(0.0f), volume_index(0.0f);
            if (volume_here) {
              volume_pos = slab_point(frame, x, int(y), zs);
              volume_index = view.volume.index_from_world(volume_pos);
              // Empty space (no extinction for the TF or the shadow TF) costs no
              // volume lookup; preintegrated segments may reach into it, so they look.
              if (!use_preintegration && view.majorant_at(volume_index) <= 0.0f &&
                  shadow.majorant_at(volume_index) <= 0.0f) {
                volume_here = false;
              }
            }
            if (volume_here) {
              value = sampler(volume_index);
              ++count;
              const float fraction = (s1 - s0) / e;
              if (use_preintegration) {
                const float front = std::isnan(p.previous_value) ? value : p.previous_value;
                const vec4 seg = preintegrated.lookup(front, value);
                const float depth_exponent = fraction / p.ray_cos;  // the segment's length in units of e
                const float keep = glm::max(1.0f - seg.a, 1e-30f);
                volume_sample = vec4(vec3(seg), 1.0f - std::pow(keep, depth_exponent));
                volume_shadow = separate_shadow_tf ? tf_lookup(shadow.tf, value).a * fraction
                                                   : -std::log(keep) / e * fraction;
              } else {
                const vec4 c = tf_lookup(view.tf, value);
                volume_sample = vec4(vec3(c), 1.0f - exp_nonpositive(-c.a * (s1 - s0) / p.ray_cos));
                volume_shadow = (separate_shadow_tf ? tf_lookup(shadow.tf, value).a : c.a) * fraction;
              }
              p.previous_value = value;
            } else {
              p.previous_value = std::numeric_limits<float>::quiet_NaN();
            }

            // The meshes: the part of the slab inside them (up to a plane).
            SlabCoverage cover;
            vec4 mesh_sample(0.0f);
            vec3 mesh_shadow(0.0f);  // per channel: transport colours
            vec3 mesh_pos(0.0f);
            if (has_meshes) {
              cover = cross_slab(meshes.ldi, p.layers, z0, glm::min(z1, p.z_plane));
              if (cover.length > 0.0f) {
                mesh_pos = slab_point(frame, x, int(y), cover.first + p.offset * (cover.last - cover.first));
                vec3 light_sigma;
                const vec4 m = meshes.medium(cover.objects, mesh_pos, light_sigma);
                mesh_sample = vec4(vec3(m), 1.0f - exp_nonpositive(-m.a * cover.length / p.ray_cos));
                mesh_shadow = light_sigma * (cover.length / e);
              }
            }

            if (!volume_here && cover.length <= 0.0f && cover.entry < 0 && !plane_here) continue;  // empty here
            for (std::size_t s = 0; s < slot_of.size(); ++s) {
              if (slot_of[s] >= 0) incoming[s] = light_at(slot_of[s], current, i);
            }
            if (shading) {
              // The highlight of the first surface entered in this slab.
              if (cover.entry >= 0) {
                const LdiFragment& f = meshes.ldi.fragments[cover.entry];
                const MeshMaterialView& mat = meshes.objects[f.object];
                const vec3 at = slab_point(frame, x, int(y), f.depth);
                vec3 highlight(0.0f);
                for (int l = 0; l < view.light_count; ++l) {
                  const LightSample ls = sample_light(view.lights[l], at);
                  const float spec = microfacet_specular(f.normal, -p.ray_dir, ls.to_light, mat.specular, mat.roughness);
                  if (spec > 0.0f && !blocked_by_planes(view, at, ls)) highlight += spec * incoming[l] * ls.radiance;
                }
                p.color += p.transmittance * highlight;
              }
              // Each part is lit at its middle and composited nearest first.
              // The volume sample's light has crossed the half of the slab in
              // front of it along the light (the ray caster's midpoint rule):
              // the medium there is sampled a quarter of the slab back toward
              // the light, so a surface facing the light is not darkened by
              // the slab it lies in (taking the sample's own extinction would
              // treat every slab as a plate across the view). Mesh samples get
              // the same within-slab correction from their own (homogeneous
              // within a layer) extinction over the covered length: lit by the
              // light entering the slab unattenuated, as in the paper, a dense
              // mesh came out too bright and striped with a brightness that
              // grew with the slab distance (issue 23).
              // With slanted paths each part's light is read where the light's
              // ray through the part's middle (depth `middle`) crossed the
              // slab's plane, not at the pixel.
              auto composite = [&](vec4 sample, const vec3* half_depth, vec3 pos, vec3 index, float v,
                                   const ScatteringLighting<BufferVisibility>& lighting, float middle) {
                if (!(sample.a > 0.0f)) return;
                const float view_depth = -std::log1p(-glm::min(sample.a, 1.0f - 1e-7f));
                const float along = (middle - z) / e;
                for (std::size_t s = 0; s < slot_of.size(); ++s) {
                  const int l = slot_of[s];
                  if (l < 0) continue;
                  vec3 in = incoming[s];
                  if (slanted && along != 0.0f) {
                    const vec2 at = vec2(float(x) + 0.5f, float(y) + 0.5f) - along * slanted_.drift(l, x, int(y));
                    in = channels == 1 ? vec3(read_buffer(buffer(l, current), width, height, at))
                                       : vec3(read_buffer(buffer(l, current, 0), width, height, at),
                                              read_buffer(buffer(l, current, 1), width, height, at),
                                              read_buffer(buffer(l, current, 2), width, height, at));
                  }
                  vis[s] = half_depth ? in * segment_light_factor(view_depth, 2.0f * half_depth[l]) : in;
                }
                ScatteringLighting<BufferVisibility> lit = lighting;
                lit.visibility.values = vis;
                const SamplePoint sp{pos, index, v, vec3(sample), 0.0f, p.ray_dir};
                p.color += (p.transmittance * sample.a) * lit.sample(sp);
                p.transmittance *= 1.0f - sample.a;
              };
              vec3 volume_half[kMaxLights];
              if (volume_sample.a > 0.0f) {
                const float fraction = (s1 - s0) / e;
                for (int l = 0; l < light_count; ++l) {
                  const float half_path = 0.5f * fraction * light_path[std::size_t(l)];
                  const vec3 q = volume_pos - 0.5f * half_path * light_travel[std::size_t(l)];
                  const float sigma = shadow_extinction(q);
                  // With slanted paths: the box's depth along the light's path
                  // from the slab's front to the part's back.
                  const float inside = slanted ? slanted_.inside_box(l, x, int(y), s1, s1) : s1 - s0;
                  volume_half[l] = vec3(sigma * half_path * (inside / (s1 - s0)));
                }
              }
              vec3 mesh_half[kMaxLights];
              if (mesh_sample.a > 0.0f) {
                const vec3 sigma = mesh_shadow * (e / cover.length);
                for (int l = 0; l < light_count; ++l) {
                  // The light crosses the mesh's depth inside along its path from
                  // the slab's front to the covered part's back (the column's
                  // covered length where the path runs straight down it).
                  const float inside = slanted_.inside_mesh(l, x, int(y), cover.last, cover.last);
                  mesh_half[l] = 0.5f * sigma * (inside / e) * light_path[std::size_t(l)];
                }
              }
              if (cover.middle < 0.5f * (s0 + s1)) {  // the parts' middles order them, wherever they sample
                composite(mesh_sample, mesh_half, mesh_pos, vec3(0.0f), 0.0f, mesh_light, cover.middle);
                composite(volume_sample, volume_half, volume_pos, volume_index, value, volume_light, 0.5f * (s0 + s1));
              } else {
                composite(volume_sample, volume_half, volume_pos, volume_index, value, volume_light, 0.5f * (s0 + s1));
                composite(mesh_sample, mesh_half, mesh_pos, vec3(0.0f), 0.0f, mesh_light, cover.middle);
              }
            }
            // (4) the light leaving this slab toward the next.
            const vec3 optical_depth = volume_shadow + mesh_shadow;
            if (has_medium) {
              has_medium[i] = max_component(optical_depth) > 0.0f;
              for (int c = 0; c < channels; ++c) slab_extinction[c][i] = optical_depth[c];
            }
            if (slanted) {  // attenuated after the loop, along the paths
              if (cover.length > 0.0f) slanted_.record_mesh(i, mesh_shadow * (e / cover.length));
              if (crosses_box) slanted_.record_volume(i, volume_shadow / ((s1 - s0) / e));
            } else if (max_component(optical_depth) > 0.0f) {
              for (int l = 0; l < light_count; ++l) {
                for (int c = 0; c < channels; ++c) {
                  buffer(l, current, c)[i] *= exp_nonpositive(-optical_depth[c] * light_path[std::size_t(l)]);
                }
              }
            }
            if (plane_here) {
              // Lit by the light that crossed this slab's medium in front of it.
              for (std::size_t s = 0; s < slot_of.size(); ++s) {
                const int l = slot_of[s];
                if (l < 0) continue;
                vis[s] = light_at(l, current, i);
                if (slanted) {  // down its column: the plane cuts the slab's paths
                  const vec3 depth = optical_depth * light_path[std::size_t(l)];
                  vis[s] *= vec3(exp_nonpositive(-depth.x), exp_nonpositive(-depth.y), exp_nonpositive(-depth.z));
                }
              }
              shade_plane(p, x, int(y), vis);
            }
          }
        }
        samples.fetch_add(count, std::memory_order_relaxed);
      });
      if (slanted) {
        for (int l = 0; l < light_count; ++l) {
          for (int c = 0; c < channels; ++c) planes[std::size_t(l * channels + c)] = buffer(l, current, c);
        }
        slanted_.attenuate(planes.data(), light_count, channels, light_path, has_medium);
      }
    }
    return 0;
  });

  // Planes beyond the last slab (capped) and the background.
  parallel_for(0, height, [&](std::int64_t first, std::int64_t last) {
    vec3 vis[kMaxSceneLights];
    for (int i = 0; i < kMaxSceneLights; ++i) vis[i] = vec3(1.0f);
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
        PixelState& p = px[i];
        if (p.guard) continue;
        if (!p.done && p.plane >= 0) {
          for (std::size_t s = 0; s < slot_of.size(); ++s) {
            if (slot_of[s] >= 0) vis[s] = light_count > 0 && slabs > 0 ? light_at(slot_of[s], current, i) : vec3(1.0f);
          }
          shade_plane(p, x, int(y), vis);
        }
        vec4 out(p.color, 1.0f - p.transmittance);
        if (!p.done) out = vec4(p.color + p.transmittance * view.background, 1.0f - p.transmittance);
        image.data()[std::size_t(x - guard) + std::size_t(image_width) * std::size_t(y - guard)] = out;
      }
    }
  });
  if (stats) {
    stats->samples += samples.load();
    stats->rays += pixels;
    stats->passes += std::uint64_t(slabs);
    // The SIMD target of the carried light's read or of a several-tap slab step.
    SimdTarget simd = carried_.target();
    for (int l = 0; l < light_count && simd == SimdTarget::Scalar; ++l) {
      if (!carried[std::size_t(l)] && convolve_row_function(kernels[std::size_t(l)].for_slab(1), pixels)) {
        simd = active_simd_target();
      }
    }
    stats->simd = simd;
  }
}

std::uint64_t SlabRenderer::aux_bytes() const {
  return buffers_.size() * sizeof(float) + carried_.bytes() + meshes_.bytes() +
         (settings_.preintegrated ? preintegration_.bytes() : 0);
}

}  // namespace penumbra
