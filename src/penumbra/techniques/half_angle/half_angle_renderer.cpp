#include "penumbra/techniques/half_angle/half_angle_renderer.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/render_lit.h"
#include "penumbra/techniques/half_angle/diffuse_blur.h"
#include "penumbra/techniques/half_angle/half_angle_kernels.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace penumbra {
namespace {

struct Rect {
  int x0, y0, x1, y1;  // [x0, x1) x [y0, y1)
};

// Pixel rectangle covering the projection of the points (the whole image if
// one lies behind the camera).
Rect eye_rect(const CameraView& c, int width, int height, const vec3* points, int count) {
  const Rect full{0, 0, width, height};
  if (count == 0) return Rect{0, 0, 0, 0};
  const float aspect = float(width) / float(height);
  vec2 lo(kInfinity), hi(-kInfinity);
  for (int i = 0; i < count; ++i) {
    const vec3 q = points[i] - c.eye;
    float sx = glm::dot(q, c.right), sy = glm::dot(q, c.up);
    if (!c.orthographic) {
      const float z = glm::dot(q, c.forward);
      if (!(z > 1e-6f)) return full;
      sx /= z;
      sy /= z;
    }
    const vec2 p((sx / (c.half_height * aspect) + 1.0f) * 0.5f * float(width),
                 (1.0f - sy / c.half_height) * 0.5f * float(height));
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return Rect{int(std::clamp(std::floor(lo.x) - 1.0f, 0.0f, float(width))),
              int(std::clamp(std::floor(lo.y) - 1.0f, 0.0f, float(height))),
              int(std::clamp(std::ceil(hi.x) + 1.0f, 0.0f, float(width))),
              int(std::clamp(std::ceil(hi.y) + 1.0f, 0.0f, float(height)))};
}

Rect light_rect(const LightCacheProjection& p, const vec3* points, int count) {
  const Rect full{0, 0, p.size, p.size};
  if (count == 0) return Rect{0, 0, 0, 0};
  if (p.mapping == LightMapping::Octahedral) return full;
  vec2 lo(kInfinity), hi(-kInfinity);
  for (int i = 0; i < count; ++i) {
    const vec3 q = p.project(points[i]);
    if (q.x < 0.0f && q.y < 0.0f) return full;
    lo = glm::min(lo, vec2(q));
    hi = glm::max(hi, vec2(q));
  }
  const float n = float(p.size);
  return Rect{int(std::clamp(std::floor(lo.x) - 1.0f, 0.0f, n)), int(std::clamp(std::floor(lo.y) - 1.0f, 0.0f, n)),
              int(std::clamp(std::ceil(hi.x) + 1.0f, 0.0f, n)), int(std::clamp(std::ceil(hi.y) + 1.0f, 0.0f, n))};
}

// The automatic light buffer size: Kniss et al.'s (the eye buffer's larger
// side), or a texel about a pixel wide at the volume's centre when that is
// finer: once the camera zooms in, a light buffer over the whole box at the
// image's size has texels several pixels wide and grazing light on thin
// surfaces bands (engine CT zoomed to a third at 160^2: mean dE 1.86 ->
// 0.81). For a light inside the box, at the box's half-diagonal.
int automatic_buffer_size(const Scene& scene) {
  const Box3 box = scene.volume().world_box();
  const Camera& camera = scene.camera();
  const RenderSettings& r = scene.render();
  const float height = camera.projection == Projection::Orthographic
                           ? camera.ortho_height
                           : 2.0f * std::tan(0.5f * glm::radians(camera.fov_deg)) * glm::length(box.center() - camera.eye);
  const float pixel = std::max(height / float(r.height), 1e-6f);
  float extent = 0.0f;
  for (const Light& light : scene.lights()) {
    if (light.type == LightType::Environment) continue;
    const LightCacheProjection p = make_light_cache_projection(light, box, 1);
    const float reach = p.mapping == LightMapping::Octahedral ? 0.5f * glm::length(box.extent()) : 0.0f;
    const float depth = light.at_infinity() ? 0.0f : glm::max(glm::length(box.center() - light.position), reach);
    extent = std::max(extent, p.texel_world_size(depth).x);
  }
  return std::clamp(std::max(int(std::ceil(extent / pixel)), std::max(r.width, r.height)), 16, 4096);
}

}  // namespace

void HalfAngleRenderer::prepare(const Scene& scene, const HalfAngleSettings& settings) {
  if (settings.light_buffer_size != 0 && (settings.light_buffer_size < 16 || settings.light_buffer_size > 4096)) {
    throw InvalidArgument("light_buffer_size", "must be 0 (automatic) or in [16, 4096]");
  }
  resources_.update(scene, scene.material().shading == Shading::Phong);
  settings_ = settings;
  const int n = settings.light_buffer_size > 0 ? settings.light_buffer_size : automatic_buffer_size(scene);
  const SceneVersions& v = scene.versions();
  if (built_ && n == size_ && v.lights == lights_version_ && v.data == data_version_) return;
  // The light buffer's projection and each texel's light ray, per light: they
  // depend on the light, the box and the buffer size, not on the camera (the
  // slicing axis enters the slice loop as two dot products per texel).
  const Box3 box = scene.volume().world_box();
  const std::size_t texels = std::size_t(n) * std::size_t(n);
  std::size_t lights = 0;
  for (const Light& light : scene.lights()) lights += light.type != LightType::Environment;
  const std::size_t stride = texels + kSlicedRowPadding;
  check_memory_budget("half-angle light rays",
                      checked_product({stride, SlicedRows::kLightFields * sizeof(float), std::uint64_t(lights)}));
  lights_.clear();
  for (const Light& light : scene.lights()) {
    if (light.type == LightType::Environment) continue;
    LightRays lr;
    lr.projection = make_light_cache_projection(light, box, n);
    lr.stride = stride;
    lr.rays.assign(SlicedRows::kLightFields * stride, 0.0f);
    const SlicedRows rows{lr.rays.data(), stride};
    parallel_for(0, n, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t y = first; y < last; ++y) {
        for (int x = 0; x < n; ++x) {
          const Ray r = lr.projection.texel_ray(vec2(float(x) + 0.5f, float(y) + 0.5f));
          const std::size_t i = std::size_t(x) + std::size_t(n) * std::size_t(y);
          for (int c = 0; c < 3; ++c) {
            rows.field(SlicedRows::kOriginX + c)[i] = r.origin[c];
            rows.field(SlicedRows::kDirectionX + c)[i] = r.direction[c];
          }
        }
      }
    });
    lights_.push_back(std::move(lr));
  }
  size_ = n;
  lights_version_ = v.lights;
  data_version_ = v.data;
  built_ = true;
  ++rebuilds_;
}

void HalfAngleRenderer::render(const Scene& scene, Image& image, RenderStats* stats) {
  const RenderView view = resources_.view(scene);
  const RenderView shadow = resources_.shadow_view(scene);
  std::vector<const Light*> lights;
  for (const Light& l : scene.lights()) {
    if (l.type != LightType::Environment) lights.push_back(&l);
  }
  if (lights.empty()) {
    render_lit(view, NoShadows{}, view.material.shading, image, stats);
    return;
  }
  const int width = view.width, height = view.height;
  if (image.width() != width || image.height() != height) image = Image(width, height);
  const int n = size_;
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  const std::size_t texels = std::size_t(n) * std::size_t(n);
  const std::size_t stride = pixels + kSlicedRowPadding;
  check_memory_budget("half-angle buffers",
                      checked_product({texels, 2 * sizeof(vec4)}) + checked_product({pixels, sizeof(vec4) + 8}) +
                          checked_product({stride, SlicedRows::kEyeFields * sizeof(float) + 1}));
  light_.resize(texels);
  blur_.resize(texels);
  sums_.assign(pixels, vec4(0.0f));
  // The viewing rays and, per pass, the eye pixels (half_angle_kernels.h).
  eye_.assign(SlicedRows::kEyeFields * stride, 0.0f);
  const SlicedRows eye{eye_.data(), stride};
  float* const red = eye.field(SlicedRows::kRed);
  float* const green = eye.field(SlicedRows::kGreen);
  float* const blue = eye.field(SlicedRows::kBlue);
  float* const transmittance = eye.field(SlicedRows::kTransmittance);
  float* const t_max = eye.field(SlicedRows::kTMax);
  auto origin = [&](std::size_t i) {
    return vec3(eye.field(SlicedRows::kOriginX)[i], eye.field(SlicedRows::kOriginY)[i],
                eye.field(SlicedRows::kOriginZ)[i]);
  };
  auto direction = [&](std::size_t i) {
    return vec3(eye.field(SlicedRows::kDirectionX)[i], eye.field(SlicedRows::kDirectionY)[i],
                eye.field(SlicedRows::kDirectionZ)[i]);
  };
  eye_plane_.assign(pixels, -1);
  int* const eye_plane = eye_plane_.data();
  parallel_for(0, height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t i = std::size_t(x) + std::size_t(width) * std::size_t(y);
        const Ray ray = view.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, width, height);
        for (int c = 0; c < 3; ++c) {
          eye.field(SlicedRows::kOriginX + c)[i] = ray.origin[c];
          eye.field(SlicedRows::kDirectionX + c)[i] = ray.direction[c];
        }
        eye_plane[i] = nearest_plane(view, ray, kInfinity, t_max[i]);
      }
    }
  });
  // The packet rows of the active SIMD target, where the view can run as
  // packets (both null: the scalar rows).
  const SimdTarget target = packet_target(view);
  const auto eye_packets =
      simd_unit_function(target, []<SimdTarget T>() { return &eye_slice_row_packets<T>; });
  const auto light_packets =
      simd_unit_function(target, []<SimdTarget T>() { return &light_slice_row_packets<T>; });
  const ForwardScattering scattering =
      make_forward_scattering(settings_.albedo, settings_.cone_angle_deg, view.material.phase_g, view.material.albedo,
                              view.volume.min_spacing());
  std::atomic<std::uint64_t> samples{0};
  plane_done_.assign(pixels, 0);
  std::uint8_t* const plane_done = plane_done_.data();
  std::vector<int> bucket_start, bucket_pixels;

  for (std::size_t li = 0; li < lights.size(); ++li) {
    const Light& light = *lights[li];
    const bool first_pass = li == 0;
    RenderView lit = view, lit_shadow = shadow;
    lit.lights = lit_shadow.lights = &light;
    lit.light_count = lit_shadow.light_count = 1;
    if (!first_pass) {
      lit.material.ambient = 0.0f;
      lit.background = vec3(0.0f);
    }
    HalfAngleKernel kernel;
    kernel.view = &lit;
    kernel.shadow = &lit_shadow;
    kernel.separate_shadow_tf = scene.shadow_transfer_function().has_value();
    kernel.slices = make_slice_setup(view.camera, light, view.box, settings_.slices, view.step);
    const SlicedRows light_rays{lights_[li].rays.data(), lights_[li].stride};
    kernel.projection = lights_[li].projection;
    kernel.light = light_.data();
    kernel.scattering = scattering;
    const SliceSetup& slices = kernel.slices;
    last_slices_ = slices.count;
    const vec3 s = slices.axis;
    std::fill(light_.begin(), light_.end(), vec4(1.0f));
    // The blur swaps the two buffers, so both start at the unlit constant (diffuse_blur.h).
    if (scattering.has_diffuse()) std::fill(blur_.begin(), blur_.end(), vec4(1.0f));
    // Eye pixels, and the slice before which each plane hit is shaded (the
    // number of slices lying before it along s), bucketed.
    bucket_start.assign(std::size_t(slices.count) + 2, 0);
    plane_slice_.assign(pixels, -1);
    int* const plane_slice = plane_slice_.data();
    const vec3 base = slices.eye_front_to_back ? vec3(0.0f) : lit.background;
    for (std::size_t i = 0; i < pixels; ++i) {
      red[i] = base.r, green[i] = base.g, blue[i] = base.b;
      transmittance[i] = 1.0f;
      plane_done[i] = 0;
      if (eye_plane[i] < 0) continue;
      const float q = glm::dot(s, origin(i) + t_max[i] * direction(i));
      const float before = std::ceil((q - slices.first) / slices.spacing);
      plane_slice[i] = int(std::clamp(before, 0.0f, float(slices.count)));
      ++bucket_start[std::size_t(plane_slice[i]) + 1];
    }
    for (std::size_t k = 1; k < bucket_start.size(); ++k) bucket_start[k] += bucket_start[k - 1];
    bucket_pixels.assign(std::size_t(bucket_start.back()), 0);
    {
      std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
      for (std::size_t i = 0; i < pixels; ++i) {
        if (plane_slice[i] >= 0) bucket_pixels[std::size_t(fill[std::size_t(plane_slice[i])]++)] = int(i);
      }
    }
    auto shade_planes = [&](int k) {
      const int b0 = bucket_start[std::size_t(k)], b1 = bucket_start[std::size_t(k) + 1];
      parallel_for(b0, b1, [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t b = first; b < last; ++b) {
          const std::size_t i = std::size_t(bucket_pixels[std::size_t(b)]);
          if (slices.eye_front_to_back && transmittance[i] <= 1.0f - lit.ert_threshold) continue;
          const vec3 q = origin(i) + t_max[i] * direction(i);
          const vec3 visibility = kernel.visibility(q, 0.0f, vec3(0.0f));
          const vec3 c = ScatteringLighting<FixedVisibility>{&lit, {visibility}, lit.material.shading}.plane(
              PlaneHit{q, eye_plane[i], direction(i)});
          vec3 color = c;
          if (slices.eye_front_to_back) {
            color = vec3(red[i], green[i], blue[i]) + transmittance[i] * c;
            transmittance[i] = 0.0f;
          } else {
            transmittance[i] = 1.0f;
          }
          red[i] = color.r, green[i] = color.g, blue[i] = color.b;
          plane_done[i] = 1;
        }
      });
    };
    // Diffuse spread per slice, in light-buffer texels^2.
    const float light_step = slices.spacing / glm::max(glm::dot(s, slices.light_travel), 1e-3f);
    const vec2 texel = kernel.projection.texel_world_size(
        light.at_infinity() ? 0.0f : glm::length(view.box.center() - light.position));
    const vec2 variance =
        scattering.has_diffuse() ? light_step * scattering.spread_per_length / (texel * texel) : vec2(0.0f);

    with_sampler(view.volume, [&](const auto& sampler) {
      vec3 polygon[12];
      TexelRect lit_area{n, n, 0, 0};  // texels some slice has attenuated, and where the blur spread them
      for (int k = 0; k < slices.count; ++k) {
        shade_planes(k);
        const int corners = slice_polygon(view.box, s, slices.position(k), polygon);
        // Each row of rect r (rows `row_width` long) in parallel: row(first
        // entry, entries, samples).
        auto rows = [&](const Rect& r, int row_width, const auto& row) {
          if (r.x1 <= r.x0) return;
          parallel_for(r.y0, r.y1, [&](std::int64_t first, std::int64_t last) {
            std::uint64_t count = 0;
            for (std::int64_t y = first; y < last; ++y) {
              row(std::size_t(r.x0) + std::size_t(row_width) * std::size_t(y), r.x1 - r.x0, count);
            }
            samples.fetch_add(count, std::memory_order_relaxed);
          });
        };
        const Rect er = eye_rect(view.camera, width, height, polygon, corners);
        rows(er, width, [&](std::size_t i, int count, std::uint64_t& taken) {
          if (eye_packets) {
            taken += eye_packets(kernel, eye, k, i, count);
          } else {
            eye_slice_row<ScalarLanes>(kernel, sampler, eye, k, i, count, taken);
          }
        });
        const Rect lr = light_rect(kernel.projection, polygon, corners);
        rows(lr, n, [&](std::size_t i, int count, std::uint64_t& taken) {
          if (light_packets) {
            taken += light_packets(kernel, light_rays, k, i, count, light_.data());
          } else {
            light_slice_row<ScalarLanes>(kernel, sampler, light_rays, k, i, count, light_.data(), taken);
          }
        });
        if (scattering.has_diffuse()) {
          blur_after_slice(light_, blur_, n, TexelRect{lr.x0, lr.y0, lr.x1, lr.y1}, lit_area, variance);
          kernel.light = light_.data();
        }
      }
      shade_planes(slices.count);
      return 0;
    });

    for (std::size_t i = 0; i < pixels; ++i) {
      vec3 color(red[i], green[i], blue[i]);
      float alpha = 1.0f - transmittance[i];
      if (plane_done[i]) {
        alpha = 1.0f;
      } else if (slices.eye_front_to_back && transmittance[i] > 1.0f - lit.ert_threshold) {
        color += transmittance[i] * lit.background;
      }
      sums_[i] += vec4(color, first_pass ? alpha : 0.0f);
    }
  }
  std::copy(sums_.begin(), sums_.end(), image.data());
  if (stats) {
    stats->simd = eye_packets ? target : SimdTarget::Scalar;
    stats->samples += samples.load();
    stats->rays += std::uint64_t(pixels) * lights.size();
  }
}

std::uint64_t HalfAngleRenderer::aux_bytes() const {
  // What the buffers hold, not what this frame used: they keep their
  // capacity when the image shrinks.
  std::uint64_t bytes = (light_.capacity() + blur_.capacity() + sums_.capacity()) * sizeof(vec4) +
                        eye_.capacity() * sizeof(float) +
                        (eye_plane_.capacity() + plane_slice_.capacity()) * sizeof(int) + plane_done_.capacity();
  for (const LightRays& lr : lights_) bytes += lr.rays.capacity() * sizeof(float);
  return bytes;
}

}  // namespace penumbra
