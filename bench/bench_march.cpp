// bench_march: samples per second of the shared marching loop next to the
// floor loops (floor_loop.h) on the same volume, image and rays, one
// thread, scalar and as packets, so the distance to the floor is one number:
//
//   build-bench/bench/bench_march [--scene SCENE.json] [--size N] [benchmark flags]
//
// Counters: samples_per_s (volume samples per second) and, for the shared
// loop, floor_ratio = its samples/s over the composite floor's at the same
// lane width. The scene's volume must be uint8 (the floor reads uint8); the
// default is the engine CT (scenes/engine.json). "dense" runs use a TF with
// no transparent values, so that the shared loop's empty-space skipping has
// nothing to skip and both loops take the same samples.
#include "floor_loop.h"

#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/render/lighting.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/render/scene_resources.h"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <functional>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace penumbra::bench {
namespace {

std::string g_scene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/engine.json";
int g_size = 256;

struct Setup {
  Scene scene;
  SceneResources resources;
  RenderView view;
};

Setup& setup(bool dense) {
  static std::map<bool, std::unique_ptr<Setup>> cache;
  auto& s = cache[dense];
  if (!s) {
    s = std::make_unique<Setup>();
    s->scene = load_scene(g_scene);
    if (s->scene.volume().type() != VoxelType::UInt8) throw std::runtime_error("bench_march needs a uint8 volume");
    RenderSettings r = s->scene.render();
    r.width = r.height = g_size;
    s->scene.set_render(r);
    s->scene.set_planes({});
    if (dense) {
      const TransferFunction& old = s->scene.transfer_function();
      std::vector<TransferFunctionPoint> points = old.points();
      for (auto& p : points) p.alpha = glm::max(p.alpha, 0.004f);
      TransferFunction tf(points);
      tf.set_range(old.range());
      tf.set_unit_length(old.unit_length());
      tf.set_density_scale(old.density_scale());
      s->scene.set_transfer_function(tf);
    }
    Material m = s->scene.material();
    m.shading = Shading::Phong;
    s->scene.set_material(m);
    s->resources.update(s->scene, true);
    s->view = s->resources.view(s->scene);
  }
  return *s;
}

SimdMode mode_of(int lanes) { return lanes == 16 ? SimdMode::Avx3 : (lanes == 8 ? SimdMode::Avx2 : SimdMode::Off); }

bool available(int lanes) {
  if (lanes == 1) return true;
  try {
    parse_simd_mode(lanes == 16 ? "avx512" : "avx2");
    return true;
  } catch (const Error&) {
    return false;
  }
}

std::map<std::pair<bool, int>, double> g_floor_rate;  // (dense, lanes) -> composite floor samples/s

std::uint64_t run_floor(const RenderView& v, int lanes, FloorStage stage, std::vector<vec4>& pixels) {
  switch (lanes) {
#if defined(PENUMBRA_SIMD_AVX3)
    case 16: return N_AVX3::floor_image_simd(v, pixels.data(), stage);
#endif
#if defined(PENUMBRA_SIMD_AVX2)
    case 8: return N_AVX2::floor_image_simd(v, pixels.data(), stage);
#endif
    default: break;
  }
  switch (stage) {
    case FloorStage::Sample: return floor_image<ScalarLanes, FloorStage::Sample>(v, pixels.data());
    case FloorStage::Extinction: return floor_image<ScalarLanes, FloorStage::Extinction>(v, pixels.data());
    case FloorStage::Composite: break;
  }
  return floor_image<ScalarLanes, FloorStage::Composite>(v, pixels.data());
}

void floor_benchmark(benchmark::State& state, FloorStage stage, bool dense) {
  const int lanes = int(state.range(0));
  if (!available(lanes)) return state.SkipWithError("not on this CPU");
  const Setup& s = setup(dense);
  std::vector<vec4> pixels(std::size_t(s.view.width) * s.view.height);
  std::uint64_t samples = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    samples += run_floor(s.view, lanes, stage, pixels);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(pixels.data());
  }
  const double rate = double(samples) / seconds;
  state.counters["samples_per_s"] = rate;
  state.counters["samples_per_frame"] = double(samples) / double(state.iterations());
  if (stage == FloorStage::Composite) g_floor_rate[{dense, lanes}] = rate;
}

template <class MakeLighting>
void shared_benchmark(benchmark::State& state, bool dense, const MakeLighting& make) {
  const int lanes = int(state.range(0));
  if (!available(lanes)) return state.SkipWithError("not on this CPU");
  Setup& s = setup(dense);
  set_thread_count(1);
  set_simd_mode(mode_of(lanes));
  Image image;
  RenderStats stats;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    render_image(s.view, [&](const auto&) { return make(s.view); }, image, &stats);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  set_simd_mode(SimdMode::Auto);
  set_thread_count(0);
  const double rate = double(stats.samples) / seconds;
  state.counters["samples_per_s"] = rate;
  state.counters["samples_per_frame"] = double(stats.samples) / double(state.iterations());
  const auto floor = g_floor_rate.find({dense, lanes});
  if (floor != g_floor_rate.end()) state.counters["floor_ratio"] = rate / floor->second;
  state.counters["lane_utilisation"] =
      double(stats.samples) / (double(stats.steps) * double(simd_width(stats.simd)) + 1e-30);
  state.SetLabel(to_string(stats.simd));
}

const auto kEmission = [](const RenderView& v) { return EmissionLighting{&v}; };
const auto kPhong = [](const RenderView& v) { return ScatteringLighting<NoShadows>{&v, NoShadows{}, Shading::Phong}; };

void add(const std::string& name, std::function<void(benchmark::State&)> run) {
  // The argument is the lane width: 1 (scalar), 8 (AVX2), 16 (AVX-512).
  benchmark::RegisterBenchmark(name.c_str(), [run](benchmark::State& st) { run(st); })
      ->Arg(1)
      ->Arg(8)
      ->Arg(16)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(1.0);
}

void register_all() {
  for (const bool dense : {true, false}) {
    const std::string tag = dense ? "dense" : "scene_tf";
    add("floor_sample/" + tag, [dense](benchmark::State& st) { floor_benchmark(st, FloorStage::Sample, dense); });
    add("floor_extinction/" + tag,
        [dense](benchmark::State& st) { floor_benchmark(st, FloorStage::Extinction, dense); });
    add("floor_composite/" + tag, [dense](benchmark::State& st) { floor_benchmark(st, FloorStage::Composite, dense); });
    add("shared_emission/" + tag, [dense](benchmark::State& st) { shared_benchmark(st, dense, kEmission); });
    add("shared_phong/" + tag, [dense](benchmark::State& st) { shared_benchmark(st, dense, kPhong); });
  }
}

}  // namespace
}  // namespace penumbra::bench

int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (i + 1 < argc && std::strcmp(argv[i], "--scene") == 0) {
      penumbra::bench::g_scene = argv[++i];
    } else if (i + 1 < argc && std::strcmp(argv[i], "--size") == 0) {
      penumbra::bench::g_size = std::atoi(argv[++i]);
    } else {
      rest.push_back(argv[i]);
    }
  }
  penumbra::bench::register_all();
  int count = int(rest.size());
  benchmark::Initialize(&count, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
