#include "penumbra/techniques/ipsvi/sweep_renderer.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/render_lit.h"
#include "penumbra/techniques/ipsvi/cache_fit.h"
#include "penumbra/techniques/ipsvi/ipsvi_ray.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

namespace penumbra {
namespace {

// The texels along a fit's longer side, the size automatic fits of several
// lights agree on (fit_ipsvi_caches).
int texels_per_side(const LightCacheProjection& p) { return std::max(p.size, p.rows); }

// How far (in texel widths) the cache's light trails the samples that wrote
// it (advance() in render()); measured in docs/ipsvi.md.
constexpr float kCacheTrailTexels = 4.0f;

struct BlockPixel {
  int x, y;
  float weight;
};

// The tape march for `target`, or nullptr where this build has none.
SegmentTapeMarch segment_tape_march(SimdTarget target) {
  return simd_unit_function(target, []<SimdTarget T>() { return &march_segment_tape<T>; });
}

// Each thread's tape of light segments (segment_tape.h), 94 KiB, kept;
// `limit` segments at most (0: its capacity).
SegmentTape& thread_tape(int limit) {
  thread_local std::unique_ptr<SegmentTape> tape = std::make_unique<SegmentTape>();
  tape->limit = limit > 0 ? std::min(limit, SegmentTape::kCapacity) : SegmentTape::kCapacity;
  return *tape;
}

}  // namespace

constexpr double kCacheTexelsPerPixel = 1.4;
// An octahedral map (a point light inside the box) covers the whole sphere
// around the light where the light lies in the part of the box the camera
// sees, toward parts of the region at every distance: at most 4 texels per
// image pixel (twice the side of a square image), which leaves the engine
// CT's map at fov 32 and 128^2 as it was (docs/ipsvi.md, "A light inside the
// box"; 1.4, the frustum maps' budget, doubled the error there). A map fitted
// to part of the sphere (the light out of view) takes the same budget, so its
// texels are finer than the whole map's.
constexpr double kMapTexelsPerPixel = 4.0;

std::vector<LightCacheProjection> fit_ipsvi_caches(const Scene& scene, const IpsviSettings& settings) {
  if (settings.cache_size != 0 && (settings.cache_size < 16 || settings.cache_size > 4096)) {
    throw InvalidArgument("cache_size", "must be 0 (automatic) or in [16, 4096]");
  }
  const Box3 box = scene.volume().world_box();
  const RenderSettings& render = scene.render();
  const std::vector<Plane>& planes = scene.planes();
  LightCacheRegion region = visible_cache_region(scene.camera().view(), render.width, render.height, box,
                                                 planes.data(), int(planes.size()));
  // Automatic: the finest any light asks for, at most three times the
  // image's longer side, so that zooming in cannot grow the cache without
  // bound; an octahedral map (light inside the box) of every direction,
  // the box's whole surface: twice that, and kMapTexelsPerPixel in all.
  // (Engine CT at fov 3, 128^2, against shadow-rays: a cap of 2x with
  // texels up to 8x long gave mean / p99 dE 0.85 / 5.7 in 5.3 MB, stripes
  // along the long texels on slanted surfaces; 3x and 4x long 0.71 / 4.9 in
  // 8.6 MB; 4x and 3x long 0.56 / 4.2 in 15 MB; the whole box at a texel per
  // pixel 0.48 / 2.5 in 175 MB.)
  const int cap = std::clamp(3 * std::max(render.width, render.height), 16, 2048);
  // And at most 1.4 texels per image pixel in all (a frustum or orthographic
  // map; octahedral maps: kMapTexelsPerPixel): zoomed in, the visible region's light-space
  // footprint holds many times the image's pixels (the frustum runs deep
  // into the box; engine CT, 128^2: 1.0x at fov 32, 3.3x at fov 16, 4.9x at
  // fov 3), so the texels grow past the pixel instead of the memory
  // (docs/ipsvi.md, "A texel budget").
  region.max_texels = kCacheTexelsPerPixel * double(render.width) * double(render.height);
  region.max_map_texels = kMapTexelsPerPixel * double(render.width) * double(render.height);
  int size = settings.cache_size;
  std::vector<LightCacheProjection> out;
  for (const Light& light : scene.lights()) {
    if (light.type == LightType::Environment) continue;  // not a single-scattering light (light.h)
    out.push_back(fit_light_cache_projection(light, box, region, 0, cap, true));
    if (out.back().mapping == LightMapping::Octahedral) {
      out.back() = fit_light_cache_projection(light, box, region, 0, 2 * cap, true);
    }
    if (settings.cache_size == 0) size = std::max(size, texels_per_side(out.back()));
  }
  for (std::size_t i = 0, k = 0; i < scene.lights().size(); ++i) {
    const Light& light = scene.lights()[i];
    if (light.type == LightType::Environment) continue;
    if (texels_per_side(out[k]) != size || (settings.cache_size > 0 && out[k].rows != size)) {
      out[k] = fit_light_cache_projection(light, box, region, size, size, settings.cache_size == 0);
    }
    ++k;
  }
  return out;
}

int ipsvi_cache_size(const Scene& scene, const IpsviSettings& settings) {
  const std::vector<LightCacheProjection> fits = fit_ipsvi_caches(scene, settings);
  return fits.empty() ? 16 : texels_per_side(fits.front());
}

void IpsviRenderer::prepare(const Scene& scene, const IpsviSettings& settings) {
  resources_.update(scene, scene.material().shading == Shading::Phong);
  const SceneVersions& v = scene.versions();
  std::vector<LightCacheProjection> fits = fit_ipsvi_caches(scene, settings);
  // One cache, sized for the largest of the lights' grids.
  std::uint64_t cache_texels = 16 * 16;
  for (const LightCacheProjection& p : fits) {
    cache_texels = std::max(cache_texels, std::uint64_t(p.size) * std::uint64_t(p.rows));
  }
  const bool channels_changed = (settings.albedo > 0.0f) != (settings_.albedo > 0.0f) ||
                                settings.light_model != settings_.light_model;
  const bool stale = !built_ || v.lights != lights_version_ || v.geometry != geometry_version_ ||
                     v.data != data_version_ || settings.cache_size != settings_.cache_size || channels_changed;
  bool refit = stale || fits.size() != lights_.size();
  for (std::size_t i = 0; !refit && i < fits.size(); ++i) refit = fits[i] != lights_[i].projection;
  settings_ = settings;
  if (!refit) return;
  // A new fit (the camera moved, or anything the cache depends on changed):
  // the projections and the caches' starting states, O(texels) ray-box tests.
  if (stale) lights_.clear();
  const Box3 box = scene.volume().world_box();
  check_memory_budget("ipsvi initial cache", checked_product({cache_texels, sizeof(vec2), std::uint64_t(fits.size())}));
  std::size_t i = 0;
  lights_.resize(fits.size());
  for (const Light& light : scene.lights()) {
    if (light.type == LightType::Environment) continue;
    LightCache& lc = lights_[i];
    lc.light = light;
    lc.projection = fits[i];
    lc.initial = initial_cache_state(lc.projection, box, scene.clip_planes());
    ++i;
  }
  if (cache_texels != cache_.capacity() || stale) {
    cache_.allocate(cache_texels, settings.albedo > 0.0f, settings.light_model == IpsviLightModel::Paper);
  }
  lights_version_ = v.lights;
  geometry_version_ = v.geometry;
  data_version_ = v.data;
  built_ = true;
  if (stale) ++rebuilds_;
  ++refits_;
}

void IpsviRenderer::render(const Scene& scene, Image& image, RenderStats* stats) {
  const RenderView view = resources_.view(scene);
  const RenderView shadow = resources_.shadow_view(scene);
  counts_ = IpsviFrameCounts{};
  if (lights_.empty()) {
    // Nothing casts shadows: ambient only, through the shared loop.
    render_lit(view, NoShadows{}, view.material.shading, image, stats);
    if (stats) counts_.view_samples = stats->samples;
    return;
  }
  const int width = view.width, height = view.height;
  if (image.width() != width || image.height() != height) image = Image(width, height);
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  sums_.assign(pixels, vec4(0.0f));
  coverage_.assign(pixels, 0.0f);
  const ForwardScattering scattering =
      make_forward_scattering(settings_.albedo, settings_.cone_angle_deg, view.material.phase_g,
                              view.material.albedo, view.volume.min_spacing());
  const bool paper = settings_.light_model == IpsviLightModel::Paper;
  const ConePhase cone_phase = paper ? make_cone_phase(view.material.phase_g, settings_.cone_angle_deg) : ConePhase{};
  const PixelRect image_rect{0, 0, width, height};
  const PixelRect volume_rect = projected_box_rect(view.camera, width, height, view.box);
  // Planes need every pixel: a floor outside the volume's footprint may lie in its shadow.
  const PixelRect rect = view.plane_count > 0 ? image_rect : volume_rect;
  std::atomic<std::uint64_t> view_samples{0}, light_samples{0}, write_samples{0}, exact_plane_rays{0},
      packet_segments{0};
  std::vector<BlockPixel> block;
  SimdTarget simd = SimdTarget::Scalar;  // what the light segments ran as

  for (std::size_t li = 0; li < lights_.size(); ++li) {
    const LightCache& lc = lights_[li];
    const bool first_pass = li == 0;
    RenderView lit = view;
    lit.lights = &lc.light;
    lit.light_count = 1;
    RenderView lit_shadow = shadow;
    lit_shadow.lights = &lc.light;
    lit_shadow.light_count = 1;
    if (!first_pass) {
      lit.material.ambient = 0.0f;
      lit.background = vec3(0.0f);
    }
    const ImageLight image_light = project_light(view.camera, width, height, lc.light);
    const SweepPlan plan = make_sweep_plan(image_light, rect, settings_.band_deg, axis_hint_);
    if (image_light.flow == LightFlow::Parallel && image_light.direction != vec2(0.0f) && !plan.zones.empty()) {
      axis_hint_ = plan.zones.front().axis;
    }
    const bool early = settings_.early_termination;
    if (early) {
      early_.compute(lit, lc.light, image_light, rect);
      counts_.prepass_samples += early_.samples();
    }
    IpsviKernel kernel;
    kernel.view = &lit;
    kernel.shadow = &lit_shadow;
    kernel.separate_shadow_tf = scene.shadow_transfer_function().has_value();
    kernel.projection = lc.projection;
    kernel.scattering = scattering;
    kernel.piecewise = settings_.piecewise_integration;
    kernel.paper = paper;
    kernel.cone_phase = cone_phase;
    // The light segments as SIMD packets where this view can have them (the
    // shadow view's volume is the view's).
    const SimdTarget target = settings_.piecewise_integration ? packet_target(lit_shadow) : SimdTarget::Scalar;
    const SegmentTapeMarch tape_march = segment_tape_march(target);
    if (tape_march) simd = target;

    with_sampler(view.volume, [&](const auto& sampler) {
      // A written texel's new light: with piecewise integration its own light
      // ray (through the texel centre) marched from the stored depth to the
      // block's mean depth, and its diffuse part spread over that distance;
      // without it the mean of the samples' light (Listing 4.1). With the
      // paper's light model the colour the segment adds (Eq. 5) as well.
      //
      // Without the diffuse part the texel is carried only to kCacheTrailTexels
      // texel widths before the written depth: a sample then marches at least
      // that far along its own light ray before it takes over a texel's value,
      // so the texel's offset from its ray (up to one texel) shows less, and
      // texels written just ahead of a sample on a grazing surface are not
      // left out of its read (the cache-grid pattern of issue 21). The diffuse
      // part's spread is tied to the written depth, so it keeps it.
      // Where a texel's light ray is marched from and how far (false: no
      // march, its new light is `step.target`).
      struct TexelStep {
        CachedLight target;
        vec3 from, to_light;
        float delta;
        vec2 center;
      };
      auto plan_step = [&](int texel, const CachedLight& stored, const CachedLight& written, TexelStep& step) {
        step.target = written;
        if (!kernel.piecewise) return false;
        const int n = kernel.cache.size;
        step.center = vec2(float(texel % n) + 0.5f, float(texel / n) + 0.5f);
        const Ray light_ray = kernel.projection.texel_ray(step.center);
        if (!scattering.has_diffuse()) {
          const vec2 texel_size = kernel.projection.texel_world_size(written.depth);
          step.target.depth = written.depth - kCacheTrailTexels * glm::max(texel_size.x, texel_size.y);
          if (!(step.target.depth > stored.depth)) {
            step.target = stored;
            return false;
          }
        }
        step.delta = step.target.depth - stored.depth;
        step.from = light_ray.at(step.target.depth);
        step.to_light = -light_ray.direction;
        return true;
      };
      auto finish_step = [&](const TexelStep& step, const CachedLight& stored, const OpticalDepth& tau) {
        CachedLight out;
        out.depth = step.target.depth;
        out.direct = stored.direct * exp_nonpositive(-tau.direct);
        if (kernel.paper) out.color = stored.color * exp_nonpositive(-tau.direct) + tau.emitted;
        if (scattering.has_diffuse()) {
          const vec2 spread = std::sqrt(step.delta * scattering.spread_per_length) /
                              kernel.projection.texel_world_size(step.target.depth);
          out.diffuse = kernel.cache.read_diffuse(step.center, spread) *
                        vec3(exp_nonpositive(-tau.diffuse.r), exp_nonpositive(-tau.diffuse.g),
                             exp_nonpositive(-tau.diffuse.b));
        }
        return out;
      };
      // The written texels of a chunk, their light rays as packets where
      // this view has them (segment_tape.h), else one at a time.
      auto advance = [&](int n, const int* texels, const CachedLight* stored, const CachedLight* written,
                         CachedLight* out) {
        TexelStep steps[IlluminationCache::kResolveChunk];
        bool marched[IlluminationCache::kResolveChunk];
        SegmentTape* tape = tape_march ? &thread_tape(settings_.segment_tape_limit) : nullptr;
        std::uint64_t samples = 0;
        if (tape) tape->begin_recording(paper);
        for (int i = 0; i < n; ++i) {
          marched[i] = plan_step(texels[i], stored[i], written[i], steps[i]);
          if (!marched[i]) {
            out[i] = steps[i].target;
          } else if (tape) {
            tape->record(steps[i].from, steps[i].to_light, &steps[i].delta, 1);
          }
        }
        if (tape && tape->count > 0) {
          tape_march(lit_shadow, scattering, *tape);
          samples += tape->samples;
          packet_segments.fetch_add(std::uint64_t(tape->count), std::memory_order_relaxed);
        }
        if (tape) tape->begin_replay();
        for (int i = 0; i < n; ++i) {
          if (!marched[i]) continue;
          const TexelStep& step = steps[i];
          OpticalDepth tau;
          if (!tape || !tape->replay(&tau, 1)) {  // one at a time, or past the tape's capacity
            tau = kernel.paper ? light_segment_depth<true>(lit_shadow, sampler, step.from, step.to_light, step.delta,
                                                           scattering, samples)
                               : light_segment_depth(lit_shadow, sampler, step.from, step.to_light, step.delta,
                                                     scattering, samples);
          }
          out[i] = finish_step(step, stored[i], tau);
        }
        write_samples.fetch_add(samples, std::memory_order_relaxed);
      };
      for (const SweepZone& zone : plan.zones) {
        cache_.reset(lc.initial, lc.projection.size, lc.projection.rows);
        kernel.cache = cache_.view(lc.projection.max_depth);
        const int other = 1 - zone.axis;
        const std::size_t line_count = zone.lines.size();
        for (std::size_t first = 0; first < line_count; first += std::size_t(settings_.line_width)) {
          block.clear();
          const std::size_t last = std::min(line_count, first + std::size_t(settings_.line_width));
          for (std::size_t l = first; l < last; ++l) {
            const SweepLine& line = zone.lines[l];
            for (int a = line.lo; a <= line.hi; ++a) {
              ivec2 p;
              p[zone.axis] = line.coordinate;
              p[other] = a;
              const float w = zone.weight(vec2(p) + vec2(0.5f));
              if (w > 0.0f) block.push_back(BlockPixel{p.x, p.y, w});
            }
          }
          parallel_for(
              0, std::int64_t(block.size()),
              [&](std::int64_t begin, std::int64_t end) {
                IpsviRayCounts counts;
                SegmentTape* tape = tape_march ? &thread_tape(settings_.segment_tape_limit) : nullptr;
                for (std::int64_t i = begin; i < end; ++i) {
                  const BlockPixel& bp = block[std::size_t(i)];
                  const Ray ray = lit.camera.pixel_ray(float(bp.x) + 0.5f, float(bp.y) + 0.5f, width, height);
                  const float exit = early ? early_.exit_depth(bp.x, bp.y) : kInfinity;
                  const float offset = pixel_sample_offset(lit, bp.x, bp.y);
                  if (tape) {
                    // The ray's light segments as packets (segment_tape.h).
                    tape->begin_recording(paper);
                    IpsviRayCounts recording;
                    trace_ipsvi_ray(kernel, sampler, ray, offset, exit, recording, tape);
                    tape_march(lit_shadow, scattering, *tape);
                    counts.light_samples += tape->samples;
                    counts.packet_segments += std::uint64_t(tape->count);
                    tape->begin_replay();
                  }
                  const vec4 c = trace_ipsvi_ray(kernel, sampler, ray, offset, exit, counts, tape);
                  const std::size_t index = std::size_t(bp.x) + std::size_t(width) * std::size_t(bp.y);
                  sums_[index] += bp.weight * vec4(vec3(c), first_pass ? c.a : 0.0f);
                  if (first_pass) coverage_[index] += bp.weight;
                }
                view_samples.fetch_add(counts.view_samples, std::memory_order_relaxed);
                light_samples.fetch_add(counts.light_samples, std::memory_order_relaxed);
                exact_plane_rays.fetch_add(counts.exact_plane_rays, std::memory_order_relaxed);
                packet_segments.fetch_add(counts.packet_segments, std::memory_order_relaxed);
              },
              8);
          cache_.resolve_chunks(advance);
          ++counts_.blocks;
        }
      }
      return 0;
    });
  }

  // Pixels no sweep reached see the background.
  const vec4 background(view.background, 0.0f);
  for (std::size_t i = 0; i < pixels; ++i) {
    image.data()[i] = sums_[i] + glm::max(1.0f - coverage_[i], 0.0f) * background;
  }
  counts_.view_samples = view_samples.load();
  counts_.light_samples = light_samples.load();
  counts_.write_samples = write_samples.load();
  counts_.exact_plane_rays = exact_plane_rays.load();
  counts_.packet_segments = packet_segments.load();
  if (stats) {
    stats->samples += counts_.view_samples;
    stats->rays += std::uint64_t(width) * std::uint64_t(height) * lights_.size();
    stats->simd = simd;
  }
}

std::uint64_t IpsviRenderer::aux_bytes() const {
  std::uint64_t bytes = cache_.bytes() + early_.bytes();
  for (const LightCache& lc : lights_) bytes += lc.initial.size() * sizeof(vec2);
  return bytes;
}

}  // namespace penumbra
