// The lane-generic kernels as packets (lane_probe.cpp, per SIMD target)
// against their scalar instances: trilinear samples of every packet voxel
// type (odd grids, positions on and beyond the borders, the last voxels of the
// buffer), gradients, precomputed normals, TF lookups, exp / log / pow, light
// directions and shadow-ray transmittance.
#include "penumbra/backends/cpu/lane_probe.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/base/rng.h"
#include "penumbra/render/lighting.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/volume/procedural.h"
#include "penumbra/volume/volume.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace penumbra {
namespace {

using ProbeFunction = void (*)(const LaneProbe&);

std::vector<std::pair<const char*, ProbeFunction>> probe_targets() {
  std::vector<std::pair<const char*, ProbeFunction>> targets;
#if defined(PENUMBRA_SIMD_AVX2)
  try {
    parse_simd_mode("avx2");
    targets.push_back({"avx2", &N_AVX2::run_lane_probe});
  } catch (const InvalidArgument&) {
  }
#endif
#if defined(PENUMBRA_SIMD_AVX3)
  try {
    parse_simd_mode("avx512");
    targets.push_back({"avx512", &N_AVX3::run_lane_probe});
  } catch (const InvalidArgument&) {
  }
#endif
  return targets;
}

std::shared_ptr<Volume> typed_volume(VoxelType type, ivec3 dims) {
  const auto source = make_procedural_volume("marschner-lobb", dims);
  auto out = std::make_shared<Volume>(dims, type);
  const float* in = source->frame_as<float>(0);
  visit_voxel_type(type, [&](auto tag) {
    using T = decltype(tag);
    T* dst = out->frame_as<T>(0);
    const bool is_signed = T(-1) < T(0);
    const double scale = sizeof(T) == 1 ? 120.0 : (sizeof(T) == 2 ? 30000.0 : 1e6);
    for (std::uint64_t i = 0; i < out->voxel_count(); ++i) {
      const double x = is_signed ? (in[i] - 0.5) * 2.0 * scale : in[i] * 2.0 * scale;
      dst[i] = std::is_floating_point_v<T> ? T(in[i]) : T(std::lround(x));
    }
    return 0;
  });
  out->center_at_origin();
  return out;
}

void expect_near_rel(float a, float b, float tolerance, const char* what, int i) {
  EXPECT_NEAR(a, b, tolerance * std::max(1.0f, std::fabs(b))) << what << " at " << i;
}

TEST(Lanes, PacketKernelsMatchTheirScalarInstances) {
  const auto targets = probe_targets();
  if (targets.empty()) GTEST_SKIP() << "this CPU or build has no SIMD target";
  for (VoxelType type : {VoxelType::UInt8, VoxelType::Int8, VoxelType::UInt16, VoxelType::Int16, VoxelType::Int32,
                         VoxelType::Float32}) {
    SCOPED_TRACE(to_string(type));
    const ivec3 dims(13, 7, 9);
    Scene scene = testing::lit_spheres(8);
    scene.set_volume(typed_volume(type, dims));
    const ValueRange range = scene.volume().value_range();
    TransferFunction tf({{0.0f, vec3(1.0f, 0.5f, 0.2f), 0.0f}, {0.4f, vec3(0.2f, 0.9f, 0.4f), 0.3f},
                         {1.0f, vec3(0.9f), 0.9f}});
    tf.set_range(vec2(range.min, range.max));
    scene.set_transfer_function(tf);
    Light point;
    point.type = LightType::Point;
    point.position = vec3(3.0f, -20.0f, 7.0f);
    scene.set_lights({point});
    SceneResources resources;
    resources.update(scene, true);
    const RenderView view = resources.view(scene);

    constexpr int kCount = 256;
    std::vector<vec3> positions(kCount);
    std::vector<float> numbers(kCount);
    Pcg32 rng(7);
    for (int i = 0; i < kCount; ++i) {
      // Inside, on the border, beyond it, and at the last voxels.
      vec3 p(rng.next_float(), rng.next_float(), rng.next_float());
      p = p * (vec3(dims) + 2.0f) - 1.0f;
      if (i % 16 == 0) p = vec3(dims - 1);
      if (i % 16 == 1) p = vec3(dims) - vec3(1.0f, 1.0f, 1.5f);
      if (i % 16 == 2) p = vec3(float(dims.x) - 1.25f, float(dims.y) - 1.0f, float(dims.z) - 1.0f);
      positions[i] = p;
      numbers[i] = i % 16 == 3 ? 100.0f : 30.0f * rng.next_float() * rng.next_float() + 1e-6f;
    }
    for (const auto& [name, run] : targets) {
      SCOPED_TRACE(name);
      std::vector<float> values(kCount), transmittance(kCount);
      std::vector<vec3> gradients(kCount), normals(kCount), elp(kCount), to_light(kCount);
      std::vector<vec4> tf_values(kCount);
      LaneProbe probe;
      probe.view = &view;
      probe.positions = positions.data();
      probe.numbers = numbers.data();
      probe.count = kCount;
      probe.values = values.data();
      probe.gradients = gradients.data();
      probe.normals = normals.data();
      probe.tf = tf_values.data();
      probe.exp_log_pow = elp.data();
      probe.to_light = to_light.data();
      probe.transmittance = transmittance.data();
      run(probe);
      with_sampler(view.volume, [&](const auto& sampler) {
        for (int i = 0; i < kCount; ++i) {
          const vec3 p = positions[i];
          const float value = sampler(p);
          expect_near_rel(values[i], value, 1e-6f, "sample", i);
          // A central difference of two float samples loses what their
          // magnitude holds: with int32 voxels near 1e6 the packet and scalar
          // instances (FMA contracted differently, e.g. by clang -O1) differ by
          // up to 0.03 = 1.5e-8 of the values; allow 1e-7 of them.
          const vec3 g = sampler.gradient(p);
          const float cancellation = 1e-7f * std::max(std::fabs(range.min), std::fabs(range.max));
          for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(gradients[i][a], g[a], 1e-5f * std::max(1.0f, std::fabs(g[a])) + cancellation)
                << "gradient at " << i;
          }
          const vec3 n = view.normals.sample(p);
          for (int a = 0; a < 3; ++a) expect_near_rel(normals[i][a], n[a], 1e-6f, "normal", i);
          const vec4 c = view.tf.lookup(values[i]);
          for (int a = 0; a < 4; ++a) expect_near_rel(tf_values[i][a], c[a], 1e-6f, "tf", i);
          const float x = numbers[i];
          expect_near_rel(elp[i].x, exp_nonpositive(-x), 1e-6f, "exp", i);
          expect_near_rel(elp[i].y, log_positive(x), 1e-6f, "log", i);
          expect_near_rel(elp[i].z, pow_unit(x / (1.0f + x), 7.5f), 1e-6f, "pow", i);
          const vec3 world = view.volume.world_from_index(p);
          const LightSample ls = sample_light(view.lights[0], world);
          for (int a = 0; a < 3; ++a) expect_near_rel(to_light[i][a], ls.to_light[a], 1e-6f, "to_light", i);
          RayStats stats;
          const float t = march_transmittance(view, sampler, Ray{world, ls.to_light}, ls.distance, 1.0f, stats);
          expect_near_rel(transmittance[i], t, 1e-5f, "transmittance", i);
        }
        return 0;
      });
    }
  }
}

// The packet min, max and clamp give glm's results bit for bit, also for
// NaN, infinities and signed zeros (simd_lanes.h maps them to MINPS/MAXPS
// with swapped operands): the scalar and packet paths must not drift apart
// where a clamp meets a NaN or a -0.
TEST(Lanes, MinMaxAndClampAreGlmsBitForBit) {
  const auto targets = probe_targets();
  if (targets.empty()) GTEST_SKIP() << "this CPU or build has no SIMD target";
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float specials[] = {nan, -nan, inf, -inf, 0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -2.5f, 1e-40f, -1e-40f, 3.0f};
  constexpr int kSpecials = int(sizeof(specials) / sizeof(specials[0]));
  constexpr int kCount = 176;  // every ordered pair of specials, padded to a multiple of 16
  std::vector<float> x(kCount, 0.0f), y(kCount, 0.0f);
  for (int i = 0; i < kSpecials * kSpecials; ++i) {
    x[std::size_t(i)] = specials[i % kSpecials];
    y[std::size_t(i)] = specials[i / kSpecials];
  }
  const Scene scene = testing::lit_spheres(8);  // any view: the probe's other outputs need one
  SceneResources resources;
  resources.update(scene);
  const RenderView view = resources.view(scene);
  auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  for (const auto& [name, run] : targets) {
    std::vector<vec3> positions(kCount, vec3(0.5f)), normals(kCount), gradients(kCount), to_light(kCount);
    std::vector<vec3> elp(kCount), out(kCount);
    std::vector<vec4> tf(kCount);
    std::vector<float> values(kCount), transmittance(kCount);
    std::vector<float> numbers(kCount, 1.0f);
    LaneProbe probe;
    probe.view = &view;
    probe.positions = positions.data();
    probe.numbers = numbers.data();
    probe.count = kCount;
    probe.values = values.data();
    probe.gradients = gradients.data();
    probe.normals = normals.data();
    probe.tf = tf.data();
    probe.exp_log_pow = elp.data();
    probe.to_light = to_light.data();
    probe.transmittance = transmittance.data();
    run(probe);  // the other outputs on ordinary inputs, then min/max on the specials
    probe.numbers = x.data();
    probe.others = y.data();
    probe.min_max_clamp = out.data();
    run(probe);
    for (int i = 0; i < kSpecials * kSpecials; ++i) {
      const float a = x[std::size_t(i)], b = y[std::size_t(i)];
      const vec3 o = out[std::size_t(i)];
      EXPECT_EQ(bits(o.x), bits(glm::min(a, b))) << name << " min(" << a << ", " << b << ")";
      EXPECT_EQ(bits(o.y), bits(glm::max(a, b))) << name << " max(" << a << ", " << b << ")";
      EXPECT_EQ(bits(o.z), bits(glm::clamp(a, -1.0f, 1.0f))) << name << " clamp(" << a << ")";
    }
  }
}

// gather4 (four consecutive floats per lane: a light-map texel) gives the
// four plain loads of its scalar instance, for indices at any alignment and
// at the table's last four floats.
TEST(Lanes, Gather4ReadsTheFourFloatsAtEachIndex) {
  const auto targets = probe_targets();
  if (targets.empty()) GTEST_SKIP() << "this CPU or build has no SIMD target";
  constexpr int kTable = 1003, kCount = 160;
  std::vector<float> table(kTable);
  for (int i = 0; i < kTable; ++i) table[std::size_t(i)] = 0.25f * float(i) - 7.0f;
  std::vector<std::int32_t> indices(kCount);
  Pcg32 rng(11);
  for (int i = 0; i < kCount; ++i) {
    indices[std::size_t(i)] = std::int32_t(rng.next_float() * float(kTable - 4));
    if (i % 16 == 5) indices[std::size_t(i)] = kTable - 4;  // the last texel: no read past the end
    if (i % 16 == 9) indices[std::size_t(i)] = 0;
  }
  for (const auto& [name, run] : targets) {
    std::vector<vec4> gathered(kCount, vec4(-1.0f));
    LaneProbe probe;
    probe.count = kCount;
    probe.table = table.data();
    probe.table_indices = indices.data();
    probe.gathered = gathered.data();
    run(probe);
    for (int i = 0; i < kCount; ++i) {
      vec4 expected;
      gather4(table.data(), indices[std::size_t(i)], expected.x, expected.y, expected.z, expected.w);
      EXPECT_EQ(gathered[std::size_t(i)], expected) << name << " index " << indices[std::size_t(i)];
    }
  }
}

}  // namespace
}  // namespace penumbra
