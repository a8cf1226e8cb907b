// The illumination cache's ping-pong: writes of a block are weighted means,
// independent of their order, never move a texel back toward the light, and
// only appear after resolve; reads are bilinear; the starting state puts each
// texel at its light ray's entry into the box.
#include "penumbra/techniques/ipsvi/illumination_cache.h"

#include <gtest/gtest.h>

#include <cstring>

namespace penumbra {
namespace {

const auto keep_written = [](int, const CachedLight&, const CachedLight& written) { return written; };

// Each texel starts at the earliest box entry among the light rays of its 3x3
// neighbourhood (so that no texel of a sample's bilinear read starts ahead of
// it on a grazing-lit face); 0 where none of them meets the box.
TEST(IlluminationCache, InitialStateStartsEveryLightRayAtTheEarliestBoxEntryAroundIt) {
  const Box3 box{vec3(-10.0f), vec3(10.0f)};
  Light light;
  light.direction = glm::normalize(vec3(0.2f, 0.3f, -1.0f));
  const LightCacheProjection p = make_light_cache_projection(light, box, 16);
  const std::vector<vec2> state = initial_cache_state(p, box, {});
  auto entry = [&](int x, int y) {
    const Ray r = p.texel_ray(vec2(float(x) + 0.5f, float(y) + 0.5f));
    const Interval hit = intersect_box(r, box, 0.0f, kInfinity);
    return hit.empty() ? kInfinity : hit.t0;
  };
  int inside = 0, earlier = 0;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const vec2 s = state[std::size_t(x + 16 * y)];
      EXPECT_EQ(s.x, 1.0f);
      float earliest = kInfinity;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (x + dx < 0 || x + dx >= 16 || y + dy < 0 || y + dy >= 16) continue;
          earliest = glm::min(earliest, entry(x + dx, y + dy));
        }
      }
      if (earliest == kInfinity) {
        EXPECT_EQ(s.y, 0.0f);
      } else {
        EXPECT_NEAR(s.y, earliest, 1e-4f);
        ++inside;
        earlier += entry(x, y) > earliest + 0.1f;
      }
    }
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(earlier, 20) << "the neighbourhood must move some starts before their own entry";
  // A clip plane moves the entry.
  const std::vector<vec2> clipped = initial_cache_state(p, box, {vec4(0.0f, 0.0f, -1.0f, 0.0f)});  // keeps z <= 0
  EXPECT_GT(clipped[8 + 16 * 8].y, state[8 + 16 * 8].y + 5.0f);
}

TEST(IlluminationCache, WritesAreWeightedMeansInAnyOrderAndOnlyAdvance) {
  auto run = [](bool reversed) {
    IlluminationCache cache;
    cache.allocate(16, true);
    cache.reset(std::vector<vec2>(16, vec2(1.0f, 2.0f)), 4, 4);
    const IlluminationCacheView v = cache.view(10.0f);
    auto a = [&] { v.write(5, 1.0f, 0.5f, 4.0f, vec3(0.8f)); };
    auto b = [&] { v.write(5, 3.0f, 0.1f, 6.0f, vec3(0.4f)); };
    auto dropped = [&] { v.write(6, 1.0f, 0.2f, 1.5f, vec3(0.0f)); };  // behind the stored depth 2
    if (reversed) {
      dropped();
      b();
      a();
    } else {
      a();
      b();
      dropped();
    }
    // Nothing shows before resolve (the readers of this block see the old state).
    EXPECT_EQ(v.state[5], vec2(1.0f, 2.0f));
    cache.resolve(keep_written);
    return std::make_pair(v.state[5], vec3(v.diffuse[5]));
  };
  const auto [state, diffuse] = run(false);
  EXPECT_NEAR(state.x, (0.5f + 3.0f * 0.1f) / 4.0f, 1e-5f);
  EXPECT_NEAR(state.y, (4.0f + 3.0f * 6.0f) / 4.0f, 1e-4f);
  EXPECT_NEAR(diffuse.r, (0.8f + 3.0f * 0.4f) / 4.0f, 1e-5f);
  const auto [state2, diffuse2] = run(true);
  EXPECT_EQ(std::memcmp(&state, &state2, sizeof(state)), 0) << "fixed-point sums do not depend on the order";
  EXPECT_EQ(std::memcmp(&diffuse, &diffuse2, sizeof(diffuse)), 0);
}

TEST(IlluminationCache, ResolveAdvancesOnlyWrittenTexelsOnce) {
  IlluminationCache cache;
  cache.allocate(16, false);
  cache.reset(std::vector<vec2>(16, vec2(1.0f, 0.0f)), 4, 4);
  const IlluminationCacheView v = cache.view(10.0f);
  v.write(3, 1.0f, 0.0f, 5.0f, vec3(0.0f));
  int calls = 0;
  cache.resolve([&](int texel, const CachedLight& stored, const CachedLight& written) {
    ++calls;
    EXPECT_EQ(texel, 3);
    EXPECT_EQ(stored.depth, 0.0f);
    CachedLight out = written;
    out.direct = stored.direct * 0.25f;
    return out;
  });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(v.state[3], vec2(0.25f, 5.0f));
  EXPECT_EQ(v.state[2], vec2(1.0f, 0.0f));
  cache.resolve([&](int, const CachedLight& s, const CachedLight&) {
    ++calls;
    return s;
  });
  EXPECT_EQ(calls, 1) << "the sums were cleared";
}

TEST(IlluminationCache, ReadsAreBilinearAndUnlitOutside) {
  IlluminationCache cache;
  cache.allocate(4, true);
  cache.reset({vec2(1.0f, 0.0f), vec2(0.0f, 4.0f), vec2(1.0f, 0.0f), vec2(0.0f, 4.0f)}, 2, 2);
  const IlluminationCacheView v = cache.view(10.0f);
  const CachedLight mid = v.read(vec2(1.0f, 1.0f), false);
  EXPECT_NEAR(mid.direct, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.depth, 2.0f, 1e-6f);
  EXPECT_NEAR(v.read(vec2(1.25f, 0.5f), false).direct, 0.25f, 1e-6f);  // 3/4 of the way to texel 1
  const CachedLight outside = v.read(vec2(-0.5f, 1.0f), false);
  EXPECT_EQ(outside.direct, 1.0f);
  EXPECT_FALSE(std::isfinite(outside.depth));
  int taps[4];
  float weights[4];
  v.taps(vec2(1.25f, 1.0f), taps, weights);
  EXPECT_NEAR(weights[0] + weights[1] + weights[2] + weights[3], 1.0f, 1e-6f);
}

// The diffuse filter keeps constants and linear ramps (its taps are symmetric
// and its weights add to 1), so it spreads light without moving or losing it.
TEST(IlluminationCache, DiffuseFilterKeepsConstantsAndRamps) {
  IlluminationCache cache;
  cache.allocate(256, true);
  cache.reset(std::vector<vec2>(256, vec2(1.0f, 0.0f)), 16, 16);
  IlluminationCacheView v = cache.view(10.0f);
  std::vector<vec4> ramp(256);
  for (int i = 0; i < 256; ++i) ramp[std::size_t(i)] = vec4(0.02f * float(i % 16), 0.5f, 0.01f * float(i / 16), 1.0f);
  v.diffuse = ramp.data();
  for (const vec2& sigma : {vec2(0.0f), vec2(0.5f), vec2(2.0f), vec2(0.7f, 3.0f)}) {
    const vec3 d = v.read_diffuse(vec2(7.3f, 8.6f), sigma);
    EXPECT_NEAR(d.r, 0.02f * (7.3f - 0.5f), 1e-4f);
    EXPECT_NEAR(d.g, 0.5f, 1e-6f);
    EXPECT_NEAR(d.b, 0.01f * (8.6f - 0.5f), 1e-4f);
  }
}

}  // namespace
}  // namespace penumbra
