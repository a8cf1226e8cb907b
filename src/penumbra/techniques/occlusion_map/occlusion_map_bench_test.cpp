// Measurements for docs/PERFORMANCE.md, run by scripts/bench-occlusion-map.sh
// (disabled in the suite: they read whole volumes and time things; nothing
// here asserts a speed). Prints one "[occlusion-map bench]" line per result.
#include "penumbra/base/parallel.h"
#include "penumbra/io/io_test_support.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

namespace penumbra {
namespace {

int runs() {
  const char* env = std::getenv("OCCLUSION_MAP_RUNS");
  return env ? std::max(1, std::atoi(env)) : 3;
}

double median_ms(const std::function<void()>& f) {
  std::vector<double> ms;
  for (int i = 0; i < runs(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

// A 512^3 uint8 synthetic: the `spheres` field (procedural.h) quantised.
std::shared_ptr<Volume> synthetic512() {
  const int n = 512;
  auto volume = std::make_shared<Volume>(ivec3(n), VoxelType::UInt8);
  std::uint8_t* v = volume->frame_as<std::uint8_t>(0);
  parallel_for(0, n, [&](std::int64_t z0, std::int64_t z1) {
    for (std::int64_t z = z0; z < z1; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const vec3 p = 2.0f * vec3(x, y, z) / float(n - 1) - 1.0f;
          v[(z * n + y) * n + x] = std::uint8_t(255.0f * procedural_value("spheres", p, ivec3(n)) + 0.5f);
        }
  }, 1);
  return volume;
}

// Table 1 of the paper: the occlusion map's build (the whole pyramid, default
// settings: half resolution, 5-tap kernel, 2 moments; and 4 moments).
TEST(OcclusionMapBench, DISABLED_Preprocessing) {
  struct Item {
    std::string name;
    std::shared_ptr<Volume> volume;
  };
  std::vector<Item> items;
  for (const char* file : {"engine_256x256x128_uint8.nhdr", "ct_head_cranium_256x256x108_int16.nhdr"}) {
    items.push_back({file, read_volume(test::shared_data_dir() / file)});
  }
  items.push_back({"synthetic 512^3 uint8", synthetic512()});
  for (const Item& item : items) {
    const ValueRange r = item.volume->value_range();
    for (const int moments : {2, 4}) {
      MomentPyramid pyramid;
      const MomentPyramidSettings settings{moments, 0.5f, 5};
      const double ms = median_ms([&] { pyramid = MomentPyramid(item.volume->view(), vec2(r.min, r.max), settings); });
      std::printf("[occlusion-map bench] preprocess %s moments %d: %.1f ms, %d levels, %.1f MiB (%.2fx the data)\n",
                  item.name.c_str(), moments, ms, pyramid.level_count(), double(pyramid.bytes()) / 1048576.0,
                  double(pyramid.bytes()) / double(item.volume->frame_bytes()));
    }
  }
}

// An iso-value change costs no rebuild: prepare() after a new iso_value (or
// TF) against the first prepare(), with rebuilds() before and after.
TEST(OcclusionMapBench, DISABLED_IsoValueChange) {
  Scene scene;
  scene.set_volume(read_volume(test::shared_data_dir() / "engine_256x256x128_uint8.nhdr"));
  const TechniqueInfo& info = find_technique("occlusion-map");
  ParameterValues params(info.parameters);
  auto technique = info.create();
  const double first = median_ms([&] {
    technique = info.create();
    technique->prepare(scene, params);
  });
  const std::uint64_t before = technique->rebuilds();
  double iso = 0.3;
  const double change = median_ms([&] {
    iso = iso > 0.6 ? 0.3 : iso + 0.1;
    params.set("iso_value", iso);
    technique->prepare(scene, params);
  });
  const double tf_change = median_ms([&] {
    scene.set_transfer_function(testing::step_tf(float(iso), vec3(1.0f), 0.5f));
    technique->prepare(scene, params);
  });
  std::printf("[occlusion-map bench] engine: first prepare %.1f ms (rebuilds %llu); iso-value change %.3f ms, TF "
              "change %.3f ms (rebuilds after %llu)\n",
              first, static_cast<unsigned long long>(before), change, tf_change,
              static_cast<unsigned long long>(technique->rebuilds()));
  EXPECT_EQ(technique->rebuilds(), before);
}

}  // namespace
}  // namespace penumbra
