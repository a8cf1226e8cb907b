#pragma once
// Viewing rays through the volume and the scene's meshes together, the
// meshes as media (mesh_media.h): the ray-casting image of a scene with
// meshes (shadow-rays). The ray is cut where the set of media changes (each
// mesh's crossings, the volume's interval, the nearest opaque plane). A piece
// with the volume alone is marched in equal steps of at most the render
// step; inside a mesh the step is at most MeshMarch::step and is shortened
// where the media are dense, to an optical depth of kMeshStepDepth (never
// below MeshMarch::min_step): there the midpoint rule integrates the light,
// which falls off exponentially into a dense medium (at a depth of 2.3 per
// step the dense box of shadow_rays_mesh_test.cpp came out 0.24 for the path
// tracer's 0.42). One sample per step at the pixel's offset along it. A
// step's media add up: alpha = 1 - exp(-(sigma_volume + sum sigma_mesh) h),
// and its light is the extinction-weighted mean of the volume's sample (lit
// with the scene's shading) and the meshes' (lit with the phase function,
// DESIGN-NOTES "Meshes"), composited front to back with early ray
// termination. Steps end at the exact crossings, so a homogeneous mesh
// integrates exactly along the view whatever the step.
//
// One ray at a time (the lane-generic lighting at one lane): the BVH walk is
// per ray. render_image_with_meshes runs it over the image's tiles on the
// CPU (no device launch; the path tracer's device path reads the meshes
// through backends/cuda/mesh_mirror.h).
#include "penumbra/base/parallel.h"
#include "penumbra/render/image.h"
#include "penumbra/render/mesh_media.h"
#include "penumbra/render/render_loop.h"

#include <atomic>
#include <cstdint>

namespace penumbra {

struct MeshMarch {
  MeshesView meshes;       // with their BVHs (MeshMedia::build_shapes)
  float step = 1.0f;       // world units: the longest step inside meshes (MeshMedia::sampling_step)
  float min_step = 0.0f;   // the shortest (MeshMedia::min_step)
  bool volume = true;      // false: the volume has no extinction anywhere, so its interval is not marched
};

// The optical depth of one step inside a mesh (march_ray_with_meshes).
inline constexpr float kMeshStepDepth = 0.1f;

// The volume's and the meshes' samples at one point of a viewing ray
// (sigma_t 0 where a medium is absent).
struct StepMedia {
  SamplePoint volume;
  SamplePoint mesh;
  PENUMBRA_HD float sigma() const { return volume.sigma_t + mesh.sigma_t; }
};

template <class Sampler>
PENUMBRA_HD StepMedia step_media(const RenderView& v, const Sampler& sampler, const MeshesView& meshes, vec3 p,
                                 vec3 direction, bool in_volume, std::uint32_t inside, std::uint64_t& samples) {
  const vec3 index = v.volume.index_from_world(p);
  StepMedia m{SamplePoint{p, index, 0.0f, vec3(0.0f), 0.0f, direction},
              SamplePoint{p, index, 0.0f, vec3(0.0f), 0.0f, direction}};
  if (in_volume && v.majorant_at(index) > 0.0f) {
    m.volume.value = sampler.template sample<ScalarLanes>(index);
    typename TransferFunctionView::Place<ScalarLanes> at;
    m.volume.sigma_t = sample_extinction<ScalarLanes>(v.tf, sampler, m.volume.value, at);
    m.volume.color = v.tf.color<ScalarLanes>(at);
    ++samples;
  }
  if (inside != 0) {
    const vec4 c = meshes.medium(inside, p);
    m.mesh.color = vec3(c);
    m.mesh.sigma_t = c.a;
    samples += std::uint64_t(bit_count(inside));
  }
  return m;
}

// One viewing ray: linear rgb and the accumulated opacity (1 where an
// opaque plane was reached), as march_ray.
template <class Sampler, class VolumeLighting, class MeshLighting>
PENUMBRA_HD vec4 march_ray_with_meshes(const RenderView& v, const Sampler& sampler, const MeshMarch& march,
                                       const Ray& ray, float offset, const VolumeLighting& volume_lighting,
                                       const MeshLighting& mesh_lighting, RayStats& stats) {
  const MeshesView& meshes = march.meshes;
  float t_plane = kInfinity;
  const int plane = nearest_plane(v, ray, kInfinity, t_plane);
  const Interval volume = march.volume ? volume_interval(v, ray, 0.0f, t_plane) : Interval{};
  // Each mesh's crossings, nearest first, and which meshes hold the ray's start.
  float crossings[Scene::kMaxMeshes][kMeshCrossings];
  int count[Scene::kMaxMeshes], next[Scene::kMaxMeshes];
  std::uint32_t inside = 0;
  for (int m = 0; m < meshes.count && m < Scene::kMaxMeshes; ++m) {
    bool in = false;
    count[m] = meshes.objects[m].sigma_max > 0.0f ? sorted_crossings(meshes, m, ray, crossings[m], in) : 0;
    next[m] = 0;
    if (in) inside |= 1u << m;
  }
  const float min_transmittance = 1.0f - v.ert_threshold;
  vec3 color(0.0f);
  float transmittance = 1.0f;
  std::uint64_t samples = 0;
  bool terminated = false;
  for (float t = 0.0f; !terminated;) {
    // The piece [t, end) over which the media do not change.
    float end = t_plane;
    for (int m = 0; m < meshes.count && m < Scene::kMaxMeshes; ++m) {
      if (next[m] < count[m]) end = glm::min(end, crossings[m][next[m]]);
    }
    const bool in_volume = !volume.empty() && t >= volume.t0 && t < volume.t1;
    if (!volume.empty()) end = glm::min(end, t < volume.t0 ? volume.t0 : (t < volume.t1 ? volume.t1 : kInfinity));
    if (!(end < kInfinity)) break;  // nothing but empty space ahead
    if (end > t && (inside != 0 || in_volume)) {
      // Equal steps in the volume alone; inside meshes steps of at most
      // march.step, shortened where the media are dense.
      const int n = inside != 0 ? 1 : glm::max(1, int(glm::ceil((end - t) / v.step)));
      const float longest = inside != 0 ? glm::min(march.step, end - t) : (end - t) / float(n);
      for (float s = t; s < end && !terminated;) {
        float h = glm::min(longest, end - s);
        const vec3 direction = ray.direction;
        StepMedia media = step_media(v, sampler, meshes, ray.at(s + offset * h), direction, in_volume, inside, samples);
        if (inside != 0 && media.sigma() * h > kMeshStepDepth && h > march.min_step) {
          h = glm::max(kMeshStepDepth / media.sigma(), march.min_step);
          media = step_media(v, sampler, meshes, ray.at(s + offset * h), direction, in_volume, inside, samples);
        }
        const float reached = glm::min(s + h, end);
        h = reached - s;
        s = h > 0.0f ? reached : end;  // (a step below the float spacing at s ends the piece)
        const float sigma = media.sigma();
        if (!(sigma > 0.0f)) continue;
        const float alpha = 1.0f - exp_nonpositive(-sigma * h);
        vec3 light(0.0f);
        if (media.volume.sigma_t > 0.0f) {
          light += (media.volume.sigma_t / sigma) * volume_lighting.sample(media.volume);
        }
        if (media.mesh.sigma_t > 0.0f) light += (media.mesh.sigma_t / sigma) * mesh_lighting.sample(media.mesh);
        color += (transmittance * alpha) * light;
        transmittance *= 1.0f - alpha;
        terminated = transmittance <= min_transmittance;  // early ray termination
      }
    }
    if (end >= t_plane) break;
    for (int m = 0; m < meshes.count && m < Scene::kMaxMeshes; ++m) {
      for (; next[m] < count[m] && crossings[m][next[m]] <= end; ++next[m]) inside ^= 1u << m;
    }
    t = end;
  }
  stats.samples += samples;
  if (terminated) return vec4(color, 1.0f - transmittance);
  if (plane >= 0) {
    const vec3 lit = volume_lighting.plane(PlaneHit{ray.at(t_plane), plane, ray.direction});
    return vec4(color + transmittance * lit, 1.0f);
  }
  return vec4(color + transmittance * v.background, 1.0f - transmittance);
}

// Every pixel of the image through march_ray_with_meshes, over 16x16 tiles
// in parallel on the CPU.
template <class VolumeLighting, class MeshLighting>
void render_image_with_meshes(const RenderView& v, const MeshMarch& march, const VolumeLighting& volume_lighting,
                              const MeshLighting& mesh_lighting, Image& image, RenderStats* stats = nullptr) {
  if (image.width() != v.width || image.height() != v.height) image = Image(v.width, v.height);
  std::atomic<std::uint64_t> total_samples{0};
  with_sampler(v.volume, [&](const auto& sampler) {
    parallel_for_tiles(v.width, v.height, 16, [&](int x0, int y0, int x1, int y1) {
      RayStats tile_stats;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          const Ray ray = v.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, v.width, v.height);
          image.at(x, y) = march_ray_with_meshes(v, sampler, march, ray, pixel_sample_offset(v, x, y),
                                                 volume_lighting, mesh_lighting, tile_stats);
        }
      }
      total_samples.fetch_add(tile_stats.samples, std::memory_order_relaxed);
    });
    return 0;
  });
  if (stats) {
    stats->samples += total_samples.load();
    stats->rays += std::uint64_t(v.width) * std::uint64_t(v.height);
  }
}

}  // namespace penumbra
