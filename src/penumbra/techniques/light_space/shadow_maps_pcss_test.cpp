// The PCSS filter of shadow-map, deep-shadow-map and cssm (issue 18,
// light_space/pcss.h) against the analytic penumbra of a sharp edge
// (tests/support/penumbra_edge.h), and their softness knobs overriding it.
//
// Model: a distant uniform light of half-angle theta over a straight edge a
// distance d above the floor casts a full (0-100 %) penumbra 2 d tan(theta);
// its profile is the circular segment of the light's disk, whose 10-90 %
// width is 1.37410 d tan(theta) (shadow_rays_area_test.cpp derives it). The
// PCSS filter is a disk of radius (d_r - d_b) tan(theta) (d_b the mean
// blocker depth), so under a planar occluder it reproduces that profile;
// the measured width differs from it by where the map puts the occluder's
// depth (inside the 2-voxel slab: d_b is not the mid-plane), by the texels
// (0.2 world units at resolution 256) and the 48 fixed taps.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/techniques/registry.h"
#include "penumbra_edge.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace penumbra {
namespace {

constexpr float kPcssSegment1090 = 1.37410f;  // 10-90 % width of a disk light's edge profile, per d tan(theta)
constexpr float kPcssEdgeDistance = 30.0f;
constexpr float kPcssTolerance = 0.15f;

float pcss_edge_width(const std::string& technique, float theta_deg) {
  Light light;
  light.type = LightType::Distant;
  light.angle_deg = theta_deg;
  const testing::EdgeScene edge = testing::edge_scene(light, kPcssEdgeDistance);
  const Image image = testing::render_with(edge.scene, technique, {{"resolution", 256.0}, {"soft", std::string("auto")}});
  const float width = testing::penumbra_width_10_90(edge, image, testing::unshadowed_floor(edge));
  const float model = kPcssSegment1090 * kPcssEdgeDistance * std::tan(glm::radians(theta_deg));
  std::printf("[pcss edge] %s theta %.0f: 10-90 width %.3f, model %.3f (%+.1f %%)\n", technique.c_str(), theta_deg,
              width, model, 100.0 * (width / model - 1.0));
  return width / model;
}

class PcssEdge : public ::testing::TestWithParam<const char*> {};

TEST_P(PcssEdge, PenumbraWidthFollowsTheLightsAngle) {
  for (float theta : {3.0f, 8.0f}) {
    EXPECT_NEAR(pcss_edge_width(GetParam(), theta), 1.0f, kPcssTolerance) << GetParam() << " at " << theta << " deg";
  }
}

INSTANTIATE_TEST_SUITE_P(ShadowMapsPcss, PcssEdge, ::testing::Values("shadow-map", "deep-shadow-map", "cssm"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

// The knob set (pcf_radius, offset_scale) or soft = off: the paper's filter,
// the light's size ignored; a light without a size: the paper's filter with
// the knob unset.
TEST(ShadowMapsPcss, KnobsAndSoftOffOverrideTheLight) {
  Light directional;
  directional.type = LightType::Directional;
  const testing::EdgeScene edge = testing::edge_scene(testing::as_distant(directional, 6.0f), kPcssEdgeDistance, 32);
  const Light distant = edge.scene.lights()[0];
  Light plain = distant;
  plain.type = LightType::Directional;
  plain.angle_deg = 0.0f;
  auto with = [&](const Light& light, const std::string& technique, ParameterSettings p) {
    Scene s = edge.scene;
    s.set_lights({light});
    p["resolution"] = 256.0;
    return testing::render_with(s, technique, p);
  };
  struct Knob {
    const char* technique;
    const char* name;
    double paper_default, other;
  };
  for (const Knob& k : {Knob{"shadow-map", "pcf_radius", 0.0, 2.0}, Knob{"cssm", "offset_scale", 1.0, 2.0},
                        Knob{"deep-shadow-map", "", 0.0, 0.0}}) {
    const ParameterSettings pcss = {{"soft", std::string("auto")}};
    const Image soft = with(distant, k.technique, pcss);
    const Image hard = with(plain, k.technique, pcss);
    EXPECT_GT(rmse(soft, hard), 1e-3) << k.technique << ": the light's size softens";
    EXPECT_LT(rmse(with(distant, k.technique, {{"soft", std::string("off")}}), hard), 1e-6)
        << k.technique << ": soft = off, the paper's filter";
    EXPECT_LT(rmse(with(distant, k.technique, {}), hard), 1e-6) << k.technique << ": off by default";
    if (std::string(k.name).empty()) continue;
    EXPECT_LT(rmse(hard, with(plain, k.technique, {{k.name, k.paper_default}})), 1e-6)
        << k.technique << ": a sizeless light, " << k.name << " unset = " << k.paper_default;
    const Image overridden = with(distant, k.technique, {{"soft", std::string("auto")}, {k.name, k.other}});
    EXPECT_GT(rmse(overridden, soft), 1e-3) << k.technique << ": " << k.name << " set, not the light";
    EXPECT_LT(rmse(overridden, with(plain, k.technique, {{k.name, k.other}})), 1e-6)
        << k.technique << ": " << k.name << " set, the light's size ignored";
  }
}

// One kernel source: the packet path (this CPU's widest, SimdMode::Auto)
// gives the scalar path's PCSS image.
TEST(ShadowMapsPcss, PacketPathMatchesScalar) {
  const SimdMode saved = simd_mode();
  Light light;
  light.type = LightType::Distant;
  light.angle_deg = 6.0f;
  const testing::EdgeScene edge = testing::edge_scene(light, kPcssEdgeDistance, 32);
  for (const char* technique : {"shadow-map", "deep-shadow-map", "cssm"}) {
    set_simd_mode(SimdMode::Off);
    const Image scalar = testing::render_with(edge.scene, technique, {{"resolution", 256.0}, {"soft", std::string("auto")}});
    set_simd_mode(SimdMode::Auto);
    const Image packets = testing::render_with(edge.scene, technique, {{"resolution", 256.0}, {"soft", std::string("auto")}});
    EXPECT_LE(rmse(packets, scalar), 1e-4) << technique;
  }
  set_simd_mode(saved);
}

}  // namespace
}  // namespace penumbra
