#include "penumbra/techniques/convolution/slab_renderer.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/lighting.h"
#include "penumbra/techniques/convolution/light_propagation.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace penumbra {
namespace {

constexpr int kMaxLights = 16;
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

}  // namespace

void SlabRenderer::prepare(const Scene& scene, const SlabSettings& settings) {
  resources_.update(scene, scene.material().shading == Shading::Phong);
  settings_ = settings;
}

void SlabRenderer::render(const Scene& scene, Image& image, RenderStats* stats) {
  const RenderView view = resources_.view(scene);
  const RenderView shadow = resources_.shadow_view(scene);
  const int width = view.width, height = view.height;
  if (image.width() != width || image.height() != height) image = Image(width, height);
  const CameraView& cam = view.camera;
  const vec3 center = view.box.center();

  // One Gaussian light and kernel per non-environment light.
  std::vector<int> slot_of(scene.lights().size(), -1);
  std::vector<GaussianLight> lights;
  for (std::size_t i = 0; i < scene.lights().size(); ++i) {
    const Light& l = scene.lights()[i];
    if (l.type == LightType::Environment) continue;
    slot_of[i] = int(lights.size());
    lights.push_back(gaussian_light(l, cam, center, settings_.light));
  }
  if (scene.lights().size() > std::size_t(kMaxLights)) {
    throw InvalidScene("lights", "convolution supports at most 16 lights");
  }
  const int light_count = int(lights.size());

  const float voxel = view.volume.min_spacing();
  const float e = settings_.slab_distance_voxels > 0.0f ? settings_.slab_distance_voxels * voxel : view.step;
  float z_front = box_depth(view.box, cam, false);
  float z_back = box_depth(view.box, cam, true);
  if (!cam.orthographic) z_front = glm::max(z_front, 1e-4f);
  const float box_extent = glm::max(z_back - z_front, 0.0f);
  const float d1 = settings_.optimal_distance_voxels > 0.0f ? settings_.optimal_distance_voxels * voxel
                                                            : glm::max(0.25f * box_extent, e);

  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  check_memory_budget("convolution buffers",
                      checked_product({pixels, 2 * std::uint64_t(light_count) * sizeof(vec3) + sizeof(PixelState)}));
  std::vector<PixelState> px(pixels);
  const float diagonal = glm::length(view.box.upper - view.box.lower);
  float plane_back = z_back;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      PixelState& p = px[std::size_t(x) + std::size_t(width) * std::size_t(y)];
      const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, width, height);
      p.ray_dir = ray.direction;
      p.ray_cos = glm::dot(ray.direction, cam.forward);
      float t_plane = kInfinity;
      p.plane = nearest_plane(view, ray, kInfinity, t_plane);
      if (p.plane >= 0) {
        p.z_plane = t_plane * p.ray_cos;
        plane_back = glm::max(plane_back, glm::min(p.z_plane, z_back + diagonal));
      }
      const Interval in = volume_interval(view, ray, 0.0f, t_plane);
      if (!in.empty()) {
        p.z_in = in.t0 * p.ray_cos;
        p.z_out = in.t1 * p.ray_cos;
      }
    }
  }
  z_back = plane_back;
  const int slabs = int(std::ceil(glm::max(z_back - z_front, 0.0f) / e));
  if (slabs > kMaxSlabs) {
    throw InvalidArgument("slab_distance", "gives more than 16384 slabs through the scene; use a larger distance");
  }
  last_slabs_ = slabs;

  buffers_.assign(2 * pixels * std::size_t(light_count), vec3(1.0f));
  std::vector<SlabKernelBuilder> kernels;
  std::vector<float> light_path;  // world length of light path per slab
  for (int l = 0; l < light_count; ++l) {
    kernels.emplace_back(settings_.kernel, settings_.kernel_samples, e * lights[std::size_t(l)].mu,
                         d1 * e * lights[std::size_t(l)].covariance,
                         mix_bits(settings_.seed * 0x2545f4914f6cdd1dULL + std::uint64_t(l)));
    light_path.push_back(e / lights[std::size_t(l)].cos_view);
  }
  const SlabFrame frame{cam, width, height, e};
  const float min_transmittance = 1.0f - view.ert_threshold;
  const bool separate_shadow_tf = scene.shadow_transfer_function().has_value();
  std::atomic<std::uint64_t> samples{0};
  int current = 0;  // which half of each light's pair holds the previous slab's light
  auto buffer = [&](int l, int half) { return buffers_.data() + (std::size_t(2 * l + half)) * pixels; };

  auto shade_plane = [&](PixelState& p, int x, int y, const vec3* vis) {
    const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, width, height);
    const PlaneHit hit{ray.at(p.z_plane / p.ray_cos), p.plane, ray.direction};
    const vec3 c = ScatteringLighting<BufferVisibility>{&view, {vis}, view.material.shading}.plane(hit);
    p.color += p.transmittance * c;
    p.transmittance = 0.0f;
    p.done = true;
  };

  with_sampler(view.volume, [&](const auto& sampler) {
    using Sampler = std::decay_t<decltype(sampler)>;
    for (int k = 0; k < slabs; ++k) {
      const float z = z_front + (float(k) + 0.5f) * e;
      const int next = 1 - current;
      for (int l = 0; l < light_count; ++l) {
        if (k == 0) continue;  // buffers start unoccluded
        convolve_slab(frame, kernels[std::size_t(l)].for_slab(k), buffer(l, current), buffer(l, next), z);
      }
      if (k > 0) current = next;
      parallel_for(0, height, [&](std::int64_t first, std::int64_t last) {
        std::uint64_t count = 0;
        vec3 vis[kMaxLights];
        for (int i = 0; i < kMaxLights; ++i) vis[i] = vec3(1.0f);
        for (std::int64_t y = first; y < last; ++y) {
          for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
            PixelState& p = px[i];
            const bool plane_here = p.plane >= 0 && p.z_plane < z + 0.5f * e;
            // The part of the slab inside the box and clip planes, sampled at
            // its middle (DESIGN-NOTES "Sampling": segments sum to the chord,
            // so a homogeneous medium integrates exactly).
            const float s0 = glm::max(z - 0.5f * e, p.z_in), s1 = glm::min(z + 0.5f * e, p.z_out);
            const float zs = 0.5f * (s0 + s1);
            const bool sample_here = s1 > s0 && !(p.plane >= 0 && p.z_plane <= zs);
            if (sample_here) {
              const float fraction = (s1 - s0) / e;
              const vec3 pos = slab_point(frame, x, int(y), zs);
              const vec3 index = view.volume.index_from_world(pos);
              const float value = sampler(index);
              const vec4 c = Sampler::kAlwaysFinite ? view.tf.lookup_finite(value) : view.tf.lookup(value);
              const float sigma_shadow =
                  separate_shadow_tf ? (Sampler::kAlwaysFinite ? shadow.tf.lookup_finite(value) : shadow.tf.lookup(value)).a
                                     : c.a;
              ++count;
              if (c.a > 0.0f && !p.done && p.transmittance > min_transmittance) {
                // Lit at the segment's middle: attenuated by the half of the
                // segment in front of it (the midpoint rule of the ray caster;
                // without it a slab thicker than the mean free path is lit as
                // if its front were its middle, too bright).
                for (std::size_t s = 0; s < slot_of.size(); ++s) {
                  if (slot_of[s] < 0) continue;
                  const float half_path = 0.5f * fraction * light_path[std::size_t(slot_of[s])];
                  vis[s] = buffer(slot_of[s], current)[i] * exp_nonpositive(-sigma_shadow * half_path);
                }
                const float alpha = 1.0f - exp_nonpositive(-c.a * (s1 - s0) / p.ray_cos);
                const SamplePoint sp{pos, index, value, vec3(c), c.a, p.ray_dir};
                const vec3 lit = ScatteringLighting<BufferVisibility>{&view, {vis}, view.material.shading}.sample(sp);
                p.color += (p.transmittance * alpha) * lit;
                p.transmittance *= 1.0f - alpha;
              }
              if (sigma_shadow > 0.0f) {
                for (int l = 0; l < light_count; ++l) {
                  buffer(l, current)[i] *= exp_nonpositive(-sigma_shadow * fraction * light_path[std::size_t(l)]);
                }
              }
            }
            if (plane_here) {
              if (!p.done) {
                for (std::size_t s = 0; s < slot_of.size(); ++s) {
                  if (slot_of[s] >= 0) vis[s] = buffer(slot_of[s], current)[i];
                }
                shade_plane(p, x, int(y), vis);
              }
            }
          }
        }
        samples.fetch_add(count, std::memory_order_relaxed);
      });
    }
    return 0;
  });

  // Planes beyond the last slab (capped) and the background.
  parallel_for(0, height, [&](std::int64_t first, std::int64_t last) {
    vec3 vis[kMaxLights];
    for (int i = 0; i < kMaxLights; ++i) vis[i] = vec3(1.0f);
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
        PixelState& p = px[i];
        if (!p.done && p.plane >= 0) {
          for (std::size_t s = 0; s < slot_of.size(); ++s) {
            if (slot_of[s] >= 0) vis[s] = light_count > 0 && slabs > 0 ? buffer(slot_of[s], current)[i] : vec3(1.0f);
          }
          shade_plane(p, x, int(y), vis);
        }
        vec4 out(p.color, 1.0f - p.transmittance);
        if (!p.done) out = vec4(p.color + p.transmittance * view.background, 1.0f - p.transmittance);
        image.data()[i] = out;
      }
    }
  });
  if (stats) {
    stats->samples += samples.load();
    stats->rays += pixels;
  }
}

std::uint64_t SlabRenderer::aux_bytes() const { return buffers_.size() * sizeof(vec3); }

}  // namespace penumbra
