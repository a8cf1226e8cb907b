// filtered-sat on real data, at the default table and cache settings, over a
// floor: the defaults against per-sample lookups, and Ament et al. 2014,
// Fig. 6 (on real data the box filter looks like the Gaussian, because little
// of the shadows' energy sits at the frequencies where the sinc oscillates),
// measured as in the paper: the CIELAB lightness difference L* (0..100).
// The data: a 128 x 128 x 64 crop from the middle of the engine CT (both
// cylinder blocks and the plates between them), so the tables stay small.
#include "penumbra/analysis/color_space.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/render/parameters.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

namespace penumbra {
namespace {

bool have_engine() {
  return std::filesystem::exists(std::filesystem::path(PENUMBRA_SHARED_DATA_DIR) / "engine_256x256x128_uint8.nhdr");
}

// scenes/engine.json's TF and light over the crop, with a floor 20 voxels
// below it, at 80 x 80 pixels.
Scene engine_crop_scene() {
  Scene scene = load_scene(std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scenes" / "engine.json");
  const Volume& full = scene.volume();
  const ivec3 lo(64, 64, 32), size(128, 128, 64);
  auto crop = std::make_shared<Volume>(size, VoxelType::UInt8);
  const std::uint8_t* src = full.frame_as<std::uint8_t>(0);
  std::uint8_t* dst = crop->frame_as<std::uint8_t>(0);
  const ivec3 d = full.dims();
  for (int z = 0; z < size.z; ++z)
    for (int y = 0; y < size.y; ++y)
      std::memcpy(dst + std::size_t(size.x) * (y + std::size_t(size.y) * z),
                  src + std::size_t(lo.x) + std::size_t(d.x) * (std::size_t(lo.y + y) + std::size_t(d.y) * (lo.z + z)),
                  std::size_t(size.x));
  crop->center_at_origin();
  scene.set_volume(crop);
  TransferFunction tf = scene.transfer_function();
  tf.set_range(vec2(0.0f, 255.0f));  // the full volume's range, as "data" resolves it there
  scene.set_transfer_function(tf);
  const Box3 box = crop->world_box();
  scene.set_planes({Plane{vec3(0.0f, 0.0f, box.lower.z - 20.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.45f, 0.45f, 0.48f)}});
  scene.set_camera(Camera::framing(box, vec3(0.7f, -0.6f, 0.55f)));
  RenderSettings r = scene.render();
  r.width = r.height = 80;
  scene.set_render(r);
  return scene;
}

// One filtered-sat instance for a test's renders, so that kept tables are
// built once (parameter changes rebuild the caches; released ones, the
// tables with them).
class FilteredSatRenderer {
 public:
  explicit FilteredSatRenderer(const Scene& scene)
      : scene_(scene), info_(find_technique("filtered-sat")), technique_(info_.create()) {}
  Image render(const ParameterSettings& settings) {
    ParameterValues values(info_.parameters);
    values.apply(settings, true);
    technique_->prepare(scene_, values);
    Image image;
    technique_->render(scene_, image);
    return image;
  }
  // The tables', caches' and floor grids' bytes after the last render.
  std::uint64_t bytes() const { return technique_->aux_bytes(); }

 private:
  const Scene& scene_;
  const TechniqueInfo& info_;
  std::unique_ptr<Technique> technique_;
};

struct LightnessDifference {
  double mean = 0.0, p99 = 0.0, max = 0.0;
};

// Over the pixels of `mask` (all without one).
LightnessDifference lightness_difference(const Image& a, const Image& b, const std::vector<bool>* mask = nullptr) {
  std::vector<double> d;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixel_count(); ++i) {
    if (mask && !(*mask)[i]) continue;
    auto lightness = [&](const Image& image) {
      return srgb_linear_to_lab(glm::clamp(vec3(image.data()[i]), vec3(0.0f), vec3(1.0f))).l;
    };
    d.push_back(std::abs(lightness(a) - lightness(b)));
    sum += d.back();
  }
  std::sort(d.begin(), d.end());
  return {sum / double(d.size()), d[d.size() * 99 / 100], d.back()};
}

// The pixels that see the floor: those whose colour follows the floor's.
std::vector<bool> floor_pixels(const Scene& scene) {
  Scene red = scene;
  std::vector<Plane> planes = red.planes();
  planes[0].color = vec3(0.9f, 0.1f, 0.1f);
  red.set_planes(planes);
  const Image a = testing::render_with(scene, "emission-absorption");
  const Image b = testing::render_with(red, "emission-absorption");
  std::vector<bool> mask(a.pixel_count());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = glm::length(vec3(a.data()[i]) - vec3(b.data()[i])) > 1e-4f;
  return mask;
}

// The defaults must not change the image: the shadow cache (at its default
// resolution and tolerance, with refined cells where its texels differ by
// more than the tolerance) and the floor grids, with the tables released,
// against the same tables read per sample, over the whole image and over the
// floor's pixels. Without the bricks (the cache read everywhere) the same
// release costs p99 5.9 L*; the bricks take memory, the tables far more.
TEST(FilteredSatOnRealData, TheDefaultCacheMatchesPerSampleLookups) {
  if (!have_engine()) GTEST_SKIP() << "the engine CT is not in " << PENUMBRA_SHARED_DATA_DIR;
  const Scene scene = engine_crop_scene();
  FilteredSatRenderer renderer(scene);
  const Image direct = renderer.render({{"shadow_cache", false}});
  const Image cached = renderer.render({});
  const std::uint64_t released = renderer.bytes();
  const Image always_cache = renderer.render({{"cache_tolerance", 1.0}});
  const std::uint64_t caches = renderer.bytes();
  renderer.render({{"cache_refinement", 0.0}});
  const std::uint64_t kept = renderer.bytes();
  testing::save_test_image(cached, "engine-crop-filtered-sat.png");
  const LightnessDifference d = lightness_difference(cached, direct);
  const std::vector<bool> floor = floor_pixels(scene);
  const LightnessDifference f = lightness_difference(cached, direct, &floor);
  const LightnessDifference plain = lightness_difference(always_cache, direct);
  std::printf("default cache vs per-sample |dL*|: mean %.3f, p99 %.3f, max %.3f; floor: mean %.3f, p99 %.3f; "
              "cache everywhere: mean %.3f, p99 %.3f; bytes: caches %llu, defaults %llu, tables kept %llu\n",
              d.mean, d.p99, d.max, f.mean, f.p99, plain.mean, plain.p99, (unsigned long long)caches,
              (unsigned long long)released, (unsigned long long)kept);
  EXPECT_LT(d.p99, 1.0);
  EXPECT_LT(d.mean, 0.25);
  EXPECT_LT(f.p99, 1.0);
  EXPECT_GT(plain.p99, 4.0 * d.p99);
  EXPECT_GT(released, caches) << "the rough cells have bricks";
  EXPECT_LT(released, kept / 4) << "the tables are released";
}

// The same on the head CT, whose skull was the defaults' worst case: its thin
// lit bone under a directional light needs bricks finer than its plane
// surfaces do (with bricks of 4^3 in every rough cell and linear probe
// misses: p99 1.43 L* at 192^2; docs/filtered-sat.md, "Adaptive bricks").
// Zoomed in (a cache cell over about 6 pixels) the cells without a brick
// show wherever their trilinear read misses: with the cube-root probe at
// 0.014 and cache_tolerance 0.02 (the defaults before), p99 1.37 L* there
// (docs/filtered-sat.md, "Zoomed in").
TEST(FilteredSatOnRealData, TheDefaultCacheMatchesPerSampleLookupsOnTheHeadCT) {
  const std::filesystem::path file = std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scenes" / "head-directional.json";
  if (!std::filesystem::exists(std::filesystem::path(PENUMBRA_SHARED_DATA_DIR) /
                               "ct_head_cranium_256x256x108_int16.nhdr")) {
    GTEST_SKIP() << "the head CT is not in " << PENUMBRA_SHARED_DATA_DIR;
  }
  Scene scene = load_scene(file);
  RenderSettings r = scene.render();
  r.width = r.height = 160;
  scene.set_render(r);
  FilteredSatRenderer renderer(scene);
  const Image direct = renderer.render({{"shadow_cache", false}});
  const Image cached = renderer.render({});
  const std::uint64_t bytes = renderer.bytes();
  const Image uniform = renderer.render({{"cache_refinement", 2.0}});
  const LightnessDifference d = lightness_difference(cached, direct);
  const LightnessDifference u = lightness_difference(uniform, direct);
  std::printf("head CT, default cache vs per-sample |dL*|: mean %.3f, p99 %.3f, max %.2f, %.1f MiB; bricks of 2^3 "
              "only: mean %.3f, p99 %.3f\n",
              d.mean, d.p99, d.max, double(bytes) / (1024.0 * 1024.0), u.mean, u.p99);
  EXPECT_LT(d.p99, 1.0);
  EXPECT_LT(d.mean, 0.1);
  EXPECT_GT(u.p99, 3.0 * d.p99) << "the finer bricks matter here";  // measured 7x

  // Zoomed in on the face (fov 12 instead of 30).
  Camera camera = scene.camera();
  camera.fov_deg = 12.0f;
  scene.set_camera(camera);
  FilteredSatRenderer zoomed(scene);
  const Image zoomed_direct = zoomed.render({{"shadow_cache", false}});
  const LightnessDifference z = lightness_difference(zoomed.render({}), zoomed_direct);
  std::printf("zoomed in (fov 12): mean %.3f, p99 %.3f, max %.2f\n", z.mean, z.p99, z.max);
  EXPECT_LT(z.p99, 1.0);
  EXPECT_LT(z.mean, 0.15);
}

// Fig. 6 at the default table and cache settings, over the floor: a box of 9
// voxels against the Gaussian of the same variance (sigma 2.6 voxels) and
// against the paper's sigma = 7 voxels.
TEST(FilteredSatOnRealData, BoxAndGaussianOfComparableWidthLookAlikeOnTheEngine) {
  if (!have_engine()) GTEST_SKIP() << "the engine CT is not in " << PENUMBRA_SHARED_DATA_DIR;
  const Scene scene = engine_crop_scene();
  FilteredSatRenderer renderer(scene);
  const Image box = renderer.render({{"filter_voxels", 9.0}});
  const Image same_variance = renderer.render({{"filter_voxels", 9.0}, {"kernel", std::string("gaussian")}});
  // filter_voxels names the box of the Gaussian's variance: sigma = w / sqrt(12).
  const Image paper_sigma =
      renderer.render({{"filter_voxels", 7.0 * std::sqrt(12.0)}, {"kernel", std::string("gaussian")}});
  const Image hard = testing::render_with(scene, "shadow-rays");
  const LightnessDifference a = lightness_difference(box, same_variance);
  const LightnessDifference b = lightness_difference(box, paper_sigma);
  const LightnessDifference h = lightness_difference(box, hard);
  std::printf("box 9 vs gaussian sigma 2.6 |dL*|: mean %.3f, p99 %.3f, max %.3f\n", a.mean, a.p99, a.max);
  std::printf("box 9 vs gaussian sigma 7   |dL*|: mean %.3f, p99 %.3f, max %.3f\n", b.mean, b.p99, b.max);
  std::printf("box 9 vs hard shadows       |dL*|: mean %.3f, p99 %.3f\n", h.mean, h.p99);
  // The paper's "well under 2% of the range" holds for the mean (measured
  // 0.19 L*) but not for every pixel once a floor is in view: the floor's
  // wide penumbrae, where the Gaussian's +-3 sigma = +-7.8 voxels reach
  // beyond the box's +-4.5, put 1% of the pixels above 2.3 L* (max 7.3).
  // The filter itself matters: against hard shadows the mean difference is
  // far larger.
  EXPECT_LT(a.mean, 0.4);
  EXPECT_LT(a.p99, 3.5);
  EXPECT_GT(h.mean, 5.0 * a.mean);
  // The paper's sigma = 7 voxels is 2.7 times the sigma of the box's
  // variance: read as voxels, its shadows are far softer than the box's
  // (measured: mean 2.6 L*, p99 24), so the figure's "comparable Gaussian"
  // cannot be sigma = 7 voxels of this data; the same variance is.
  EXPECT_GT(b.mean, 5.0 * a.mean);
}

// The measurement behind docs/filtered-sat.md's tables of the defaults
// against per-sample lookups on whole scenes (slow: run it by name with
// --gtest_also_run_disabled_tests). Per scene, at the defaults and with the
// finest bricks of 8^3: |dL*| mean and p99 against shadow_cache=false, and
// aux_bytes.
TEST(FilteredSatOnRealData, DISABLED_DefaultCacheOnWholeScenes) {
  if (!have_engine()) GTEST_SKIP() << "the engine CT is not in " << PENUMBRA_SHARED_DATA_DIR;
  const char* names[] = {"engine", "engine-point", "head-directional", "head-point", "memory-256-two-lights"};
  for (const char* name : names) {
    Scene scene = load_scene(std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scenes" / (std::string(name) + ".json"));
    RenderSettings r = scene.render();
    r.width = r.height = std::string(name).rfind("memory", 0) == 0 ? 128 : 192;
    scene.set_render(r);
    FilteredSatRenderer reference(scene);
    const Image direct = reference.render({{"shadow_cache", false}});
    for (const double refine : {6.0, 8.0}) {
      FilteredSatRenderer renderer(scene);
      const Image cached = renderer.render({{"cache_refinement", refine}});
      const LightnessDifference d = lightness_difference(cached, direct);
      std::printf("%s cache_refinement %.0f: mean %.3f p99 %.3f max %.2f, aux %.1f MiB\n", name, refine, d.mean,
                  d.p99, d.max, double(renderer.bytes()) / (1024.0 * 1024.0));
    }
  }
}

}  // namespace
}  // namespace penumbra
