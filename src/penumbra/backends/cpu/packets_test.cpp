// The packet path against the scalar path: every technique, rendered one ray
// at a time and as AVX2 and AVX-512 packets (those this CPU has), gives the
// same image within RMSE 1e-4 (linear), on procedural scenes of every voxel
// type the packets read and on the real CT volumes; and the techniques with a
// packet path really take it.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/volume/volume.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace penumbra {
namespace {

// Restores the process-wide mode when a test ends.
struct SimdModeGuard {
  SimdMode saved = simd_mode();
  ~SimdModeGuard() { set_simd_mode(saved); }
};

std::vector<SimdMode> packet_modes() {
  std::vector<SimdMode> modes;
  for (const char* name : {"avx2", "avx512"}) {
    try {
      modes.push_back(parse_simd_mode(name));
    } catch (const InvalidArgument&) {
      // not on this CPU or in this build
    }
  }
  return modes;
}

// The volume re-quantised to another voxel type over [0, scale].
std::shared_ptr<Volume> converted(const Volume& source, VoxelType type, float scale, float offset) {
  auto out = std::make_shared<Volume>(source.dims(), type);
  out->set_spacing(source.spacing());
  out->set_origin(source.origin());
  const std::uint64_t n = source.voxel_count();
  const float* in = source.frame_as<float>(0);
  visit_voxel_type(type, [&](auto tag) {
    using T = decltype(tag);
    T* dst = out->frame_as<T>(0);
    for (std::uint64_t i = 0; i < n; ++i) dst[i] = T(std::lround(offset + in[i] * scale));
    return 0;
  });
  return out;
}

struct PacketScene {
  std::string name;
  Scene scene;
};

std::vector<PacketScene> packet_scenes() {
  std::vector<PacketScene> scenes;
  {
    Scene s = testing::with_floor(testing::lit_spheres(40));
    scenes.push_back({"spheres-float32-floor", s});
  }
  {
    Scene s = testing::lit_spheres(40);
    Light point;
    point.type = LightType::Point;
    point.position = vec3(20.0f, -40.0f, 30.0f);
    point.intensity = 3000.0f;
    s.set_lights({s.lights()[0], point});
    Material m;
    m.shading = Shading::Phong;
    m.ambient = 0.1f;
    s.set_material(m);
    s.set_clip_planes({vec4(0.2f, 0.1f, 1.0f, 3.0f)});
    RenderSettings r = s.render();
    r.jitter = true;
    r.ert_threshold = 0.95f;
    s.set_render(r);
    scenes.push_back({"spheres-phong-two-lights-clipped-jittered", s});
  }
  // Integer voxel types, odd sizes (so rows do not align with words) and a
  // grid that ends within a word of the last sample.
  const struct {
    VoxelType type;
    float scale, offset;
  } types[] = {{VoxelType::UInt8, 255.0f, 0.0f},
               {VoxelType::Int8, 200.0f, -100.0f},
               {VoxelType::UInt16, 4000.0f, 0.0f},
               {VoxelType::Int16, 3000.0f, -1000.0f},
               {VoxelType::Int32, 50000.0f, -20000.0f}};
  for (const auto& t : types) {
    Scene s = testing::with_floor(testing::lit_spheres(36));
    const auto odd = make_procedural_volume("spheres", ivec3(29, 31, 27));
    const auto v = converted(*odd, t.type, t.scale, t.offset);
    s.set_volume(v);
    TransferFunction tf = s.transfer_function();
    tf.set_range(vec2(t.offset, t.offset + t.scale));
    s.set_transfer_function(tf);
    s.set_camera(Camera::framing(v->world_box(), glm::normalize(vec3(0.3f, -1.0f, 0.4f))));
    scenes.push_back({"spheres-" + std::string(to_string(t.type)), s});
  }
  const std::filesystem::path data = PENUMBRA_SHARED_DATA_DIR;
  if (std::filesystem::exists(data / "engine_256x256x128_uint8.nhdr")) {
    scenes.push_back({"engine-ct", testing::repository_scene("scenes/engine.json", 40)});
    Scene s = testing::repository_scene("scenes/engine-point.json", 40);
    scenes.push_back({"engine-point", s});
  }
  if (std::filesystem::exists(data / "ct_head_cranium_256x256x108_int16.nhdr")) {
    scenes.push_back({"head-ct-int16-point", testing::repository_scene("scenes/head-point.json", 40)});
  }
  return scenes;
}

// Parameters that keep the slow techniques quick at test sizes.
ParameterSettings quick_params(const TechniqueInfo& info) {
  ParameterSettings p;
  if (info.name == "pathtrace") p["spp"] = 4.0;
  const ParameterSpec* resolution = info.parameters.find("resolution");
  if (resolution && resolution->min <= 256.0 && 256.0 <= resolution->max) p["resolution"] = 256.0;
  return p;
}

// The techniques whose render is the shared loop with a packet-capable
// Lighting (every render_lit technique, emission-absorption and phong), and
// occlusion-map, whose soft-shadow marches run as packets, ipsvi, whose
// light segments do, convolution, whose carried light is read as them
// (and a soft light's slab step, a variant below), and half-angle, whose eye
// and light rows are.
const std::set<std::string> kPacketTechniques = {"emission-absorption", "phong",         "shadow-rays",
                                                 "filtered-sat",        "sat-ao",        "cone-shadows",
                                                 "ambient-scattering",  "shadow-map",    "deep-shadow-map",
                                                 "cssm",                "occlusion-map", "ipsvi",
                                                 "convolution",         "half-angle"};

// Prepares once (light-space structures do not depend on the packet mode;
// building them once per scene rather than per mode keeps this test quick)
// and renders in `mode`.
Image render_mode(Technique& technique, const Scene& scene, SimdMode mode, RenderStats& stats) {
  set_simd_mode(mode);
  Image image;
  technique.render(scene, image, &stats);
  return image;
}

double max_difference(const Image& a, const Image& b) {
  double m = 0.0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      const vec4 d = glm::abs(a.at(x, y) - b.at(x, y));
      m = std::max({m, double(d.r), double(d.g), double(d.b), double(d.a)});
    }
  }
  return m;
}

// Modes of a technique that take another packet path than its defaults:
// occlusion-map's DVR mode lights every DVR sample as packets; ipsvi's
// light segments carry the diffuse part's optical depth when albedo > 0 and
// the colour they add with the paper's light model; convolution's soft light
// steps its buffers with several taps as packets; half-angle's diffuse part
// (albedo > 0) adds the diffuse attenuation to its rows.
const std::vector<std::pair<std::string, ParameterSettings>> kPacketVariants = {
    {"occlusion-map", {{"mode", std::string("dvr")}}},
    {"ipsvi", {{"albedo", 0.5}}},
    {"ipsvi", {{"light_model", std::string("paper")}}},
    {"convolution", {{"light_sigma_x2", 0.01}, {"light_sigma_y2", 0.004}}},
    {"half-angle", {{"albedo", 0.5}}}};

TEST(PacketPath, EveryTechniqueMatchesTheScalarPath) {
  const std::vector<SimdMode> modes = packet_modes();
  if (modes.empty()) GTEST_SKIP() << "this CPU or build has no SIMD target";
  SimdModeGuard guard;
  std::vector<std::pair<const TechniqueInfo*, ParameterSettings>> cases;
  for (const TechniqueInfo& info : technique_registry()) cases.push_back({&info, {}});
  for (const auto& [name, settings] : kPacketVariants) cases.push_back({&find_technique(name), settings});
  for (const PacketScene& ps : packet_scenes()) {
    for (const auto& [technique_info, variant] : cases) {
      const TechniqueInfo& info = *technique_info;
      SCOPED_TRACE(ps.name + " x " + info.name + (variant.empty() ? "" : " (variant)"));
      auto technique = info.create();
      ParameterValues params(info.parameters);
      params.apply(quick_params(info), true);
      params.apply(variant, true);
      set_simd_mode(SimdMode::Off);
      technique->prepare(ps.scene, params);
      RenderStats scalar_stats;
      const Image scalar = render_mode(*technique, ps.scene, SimdMode::Off, scalar_stats);
      EXPECT_EQ(scalar_stats.simd, SimdTarget::Scalar);
      for (SimdMode mode : modes) {
        RenderStats stats;
        const Image packets = render_mode(*technique, ps.scene, mode, stats);
        const SimdTarget expected = mode == SimdMode::Avx3 ? SimdTarget::Avx3 : SimdTarget::Avx2;
        SCOPED_TRACE(to_string(expected));
        if (kPacketTechniques.count(info.name)) {
          EXPECT_EQ(stats.simd, expected) << "the technique did not take its packet path";
        }
        EXPECT_LE(rmse(packets, scalar), 1e-4) << "max difference " << max_difference(packets, scalar);
        EXPECT_EQ(stats.samples, scalar_stats.samples);
      }
    }
  }
}

// half-angle with a point light inside the volume: its light buffer is the
// octahedral map, whose projection the packets take lane by lane
// (LightCacheProjection::project). The packet scenes above have no light
// inside a box.
TEST(PacketPath, HalfAngleWithALightInsideTheVolume) {
  const std::vector<SimdMode> modes = packet_modes();
  if (modes.empty()) GTEST_SKIP() << "this CPU or build has no SIMD target";
  SimdModeGuard guard;
  Scene scene = testing::lit_spheres(40);
  Light point;
  point.type = LightType::Point;
  point.position = scene.volume().world_box().center() + vec3(3.0f, -2.0f, 1.0f);
  point.intensity = 400.0f;
  scene.set_lights({point});
  const TechniqueInfo& info = find_technique("half-angle");
  auto technique = info.create();
  ParameterValues params(info.parameters);
  params.apply({{"albedo", 0.3}}, true);
  set_simd_mode(SimdMode::Off);
  technique->prepare(scene, params);
  RenderStats scalar_stats;
  const Image scalar = render_mode(*technique, scene, SimdMode::Off, scalar_stats);
  double lit = 0.0;
  for (int y = 0; y < scalar.height(); ++y) {
    for (int x = 0; x < scalar.width(); ++x) lit += double(scalar.at(x, y).r);
  }
  EXPECT_GT(lit / double(scalar.width() * scalar.height()), 0.01) << "the light reaches the image";
  for (SimdMode mode : modes) {
    RenderStats stats;
    const Image packets = render_mode(*technique, scene, mode, stats);
    const SimdTarget expected = mode == SimdMode::Avx3 ? SimdTarget::Avx3 : SimdTarget::Avx2;
    SCOPED_TRACE(to_string(expected));
    EXPECT_EQ(stats.simd, expected);
    EXPECT_LE(rmse(packets, scalar), 2e-6) << "max difference " << max_difference(packets, scalar);
    EXPECT_EQ(stats.samples, scalar_stats.samples);
  }
}

TEST(PacketPath, ModesParseAndNameTheirTargets) {
  SimdModeGuard guard;
  EXPECT_EQ(parse_simd_mode("off"), SimdMode::Off);
  EXPECT_EQ(parse_simd_mode("auto"), SimdMode::Auto);
  EXPECT_THROW(parse_simd_mode("sse9"), InvalidArgument);
  set_simd_mode(SimdMode::Off);
  EXPECT_EQ(active_simd_target(), SimdTarget::Scalar);
  EXPECT_STREQ(to_string(SimdTarget::Avx3), "avx512");
  EXPECT_EQ(simd_width(SimdTarget::Avx2), 8);
  for (SimdMode mode : packet_modes()) {
    set_simd_mode(mode);
    EXPECT_NE(active_simd_target(), SimdTarget::Scalar);
  }
}

TEST(PacketPath, VolumesPacketsCannotReadRenderScalar) {
  SimdModeGuard guard;
  const std::vector<SimdMode> modes = packet_modes();
  if (modes.empty()) GTEST_SKIP() << "this CPU or build has no SIMD target";
  set_simd_mode(modes.back());
  Scene s = testing::lit_spheres(16);
  s.set_volume(converted(*make_procedural_volume("spheres", ivec3(12)), VoxelType::Float64, 1.0f, 0.0f));
  RenderStats stats;
  auto t = find_technique("phong").create();
  t->prepare(s, ParameterValues(find_technique("phong").parameters));
  Image image;
  t->render(s, image, &stats);
  EXPECT_EQ(stats.simd, SimdTarget::Scalar);
}

}  // namespace
}  // namespace penumbra
