// The device choice and the CUDA backend.
//
// On every machine: `--device` parsing, that Auto renders on the CPU where no
// GPU is present, and what the device cache uploads when (through host
// memory: DeviceMirror and DeviceCache are plain host code).
//
// On a machine with a CUDA device (skipped elsewhere, as ctest skips): every
// technique with a CUDA path renders the same images on both devices, on a
// procedural scene, the engine CT and the head CT (pathtrace also on a mesh
// scene, within its standard error); a light move and a TF
// change on the device give the image of a fresh render; an unchanged scene
// uploads nothing; a device memory budget too small gives OutOfMemoryBudget.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/backends/cuda/device_cache.h"
#include "penumbra/backends/cuda/device_mirror.h"
#include "penumbra/backends/cuda/mesh_mirror.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/pathtrace/pathtrace.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra {
namespace {

struct DeviceModeGuard {
  DeviceMode saved = device_mode();
  std::uint64_t budget = device_memory_budget_bytes();
  ~DeviceModeGuard() {
    set_device_mode(saved);
    set_device_memory_budget_bytes(budget);
  }
};

TEST(Device, ModesParseAndUnknownNamesNameTheOption) {
  EXPECT_EQ(parse_device_mode("auto"), DeviceMode::Auto);
  EXPECT_EQ(parse_device_mode("cpu"), DeviceMode::Cpu);
  try {
    parse_device_mode("gpu");
    FAIL() << "'gpu' was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "--device");
  }
  if (!cuda_built() || cuda_device_count() == 0) {
    EXPECT_THROW(parse_device_mode("cuda"), InvalidArgument);
  } else {
    EXPECT_EQ(parse_device_mode("cuda"), DeviceMode::Cuda);
  }
  EXPECT_STREQ(to_string(Device::Cuda), "cuda");
  EXPECT_STREQ(to_string(Device::Cpu), "cpu");
}

TEST(Device, AutoRendersOnTheCpuWithoutAGpu) {
  if (cuda_built() && cuda_device_count() > 0) GTEST_SKIP() << "a CUDA device is present";
  DeviceModeGuard guard;
  set_device_mode(DeviceMode::Auto);
  EXPECT_EQ(active_device(), Device::Cpu);
  const TechniqueInfo& info = find_technique("phong");
  auto technique = info.create();
  const Scene scene = testing::lit_spheres(16);
  technique->prepare(scene, ParameterValues(info.parameters));
  Image image;
  RenderStats stats;
  technique->render(scene, image, &stats);
  EXPECT_EQ(stats.device, Device::Cpu);
  EXPECT_GT(stats.samples, 0u);
}

// The mirror of a view, through host memory: every array copied with its
// contents, uploaded again only when a version it depends on changes.
TEST(DeviceMirror, UploadsAnArrayOnlyWhenWhatItDependsOnChanged) {
  Scene scene = testing::with_floor(testing::lit_spheres(16));
  SceneResources resources;
  resources.update(scene, true);
  RenderView host = resources.view(scene);
  DeviceCache cache(host_memory());

  const auto mirror_once = [&](const RenderView& view) {
    cache.begin_frame();
    DeviceMirror mirror(cache, view);
    const RenderView* d = mirror.view(view);
    EXPECT_EQ(mirror.view(view), d) << "one device copy per host view and frame";
    RenderView copy = *d;
    cache.end_frame();
    return copy;
  };
  const RenderView d = mirror_once(host);
  const std::uint64_t first = cache.uploads();
  // volume, macrocells, majorants, empty distances, TF entries and sigma, normals
  EXPECT_EQ(first, 7u);
  ASSERT_NE(d.volume.data, host.volume.data);
  const std::size_t volume_bytes = std::size_t(host.volume.dims.x) * host.volume.dims.y * host.volume.dims.z *
                                   voxel_size(host.volume.type);
  EXPECT_EQ(std::memcmp(d.volume.data, host.volume.data, volume_bytes), 0);
  EXPECT_EQ(std::memcmp(d.tf.sigma, host.tf.sigma, sizeof(float) * host.tf.size), 0);
  ASSERT_EQ(d.light_count, host.light_count);
  EXPECT_NE(d.lights, host.lights);
  EXPECT_EQ(d.lights[0].intensity, host.lights[0].intensity);
  ASSERT_EQ(d.plane_count, 1);
  EXPECT_EQ(d.planes[0].color, host.planes[0].color);
  EXPECT_EQ(d.device_state, nullptr);

  // Unchanged scene, moved camera: nothing uploaded.
  mirror_once(host);
  Scene moved = scene;
  Camera camera = moved.camera();
  camera.eye += vec3(1.0f, 0.0f, 0.0f);
  moved.set_camera(camera);
  mirror_once(resources.view(moved));
  EXPECT_EQ(cache.uploads(), first);

  // A TF change: the TF tables, majorants, empty distances and macrocells
  // again, not the volume or its normals.
  Scene edited = scene;
  TransferFunction tf = edited.transfer_function();
  tf.set_range(edited.tf_value_range() * 1.5f);
  edited.set_transfer_function(tf);
  resources.update(edited, true);
  const RenderView after_tf = mirror_once(resources.view(edited));
  EXPECT_EQ(cache.uploads(), first + 5);
  EXPECT_EQ(after_tf.volume.data, d.volume.data);

  // A technique structure follows the technique's rebuild count.
  std::vector<float> table(64, 1.0f);
  const auto structure_once = [&](std::uint64_t rebuilds) {
    RenderView v = resources.view(edited);
    v.structures = rebuilds;
    cache.begin_frame();
    DeviceMirror mirror(cache, v);
    mirror.view(v);
    const float* device = mirror.structure(table.data(), table.size());
    const float value = device[0];
    cache.end_frame();
    return value;
  };
  const std::uint64_t before = cache.uploads();
  EXPECT_EQ(structure_once(1), 1.0f);
  table[0] = 2.0f;
  EXPECT_EQ(structure_once(1), 1.0f) << "same version: the old upload stays";
  EXPECT_EQ(structure_once(2), 2.0f) << "a rebuild uploads again";
  EXPECT_EQ(cache.uploads(), before + 2);
}

// One host array mirrored under two versions in one frame (the scene's
// volume that is also a mesh's texture): the first copy stays readable until
// the next frame begins, and then its memory is released.
TEST(DeviceCache, AMirrorHandedOutThisFrameOutlivesAnotherVersion) {
  DeviceCache cache(host_memory());
  std::vector<float> host(256, 3.0f);
  cache.begin_frame();
  const auto* first = static_cast<const float*>(cache.persistent(host.data(), 1024, 1, "a"));
  const auto* second = static_cast<const float*>(cache.persistent(host.data(), 1024, 2, "b"));
  ASSERT_NE(first, second);
  EXPECT_EQ(first[255], 3.0f);  // not freed (ASan would report a read of freed memory)
  EXPECT_EQ(second[0], 3.0f);
  EXPECT_EQ(cache.bytes(), 2048u);
  cache.end_frame();
  cache.begin_frame();
  EXPECT_EQ(cache.bytes(), 1024u) << "the replaced copy is released with the frame";
  cache.persistent(host.data(), 1024, 2, "b");
  cache.end_frame();
  EXPECT_EQ(cache.bytes(), 1024u);
}

TEST(DeviceMirror, ABudgetTooSmallIsAClearError) {
  DeviceModeGuard guard;
  const Scene scene = testing::lit_spheres(16);
  SceneResources resources;
  resources.update(scene);
  const RenderView host = resources.view(scene);
  DeviceCache cache(host_memory());
  set_device_memory_budget_bytes(1024);
  cache.begin_frame();
  DeviceMirror mirror(cache, host);
  try {
    mirror.view(host);
    FAIL() << "the volume fit in 1 KiB";
  } catch (const OutOfMemoryBudget& e) {
    EXPECT_NE(std::string(e.what()).find("device memory for the volume"), std::string::npos) << e.what();
  }
  EXPECT_LE(cache.bytes(), 1024u);
}

// The meshes as media, mirrored through host memory: every array the views
// reach is a copy (noise table, texture, TF tables, BVH), and the copies give
// the same media and surface crossings as the host views; an unchanged scene
// uploads them once.
TEST(DeviceMirror, MirrorsTheMeshesAsMedia) {
  std::vector<Scene> scenes{testing::repository_scene("scenes/mesh-sphere.json", 16)};
  if (std::filesystem::exists(testing::shared_data_dir() / "bucky_32x32x32_uint8.nhdr")) {
    scenes.push_back(testing::repository_scene("scenes/sphere-texture-colour.json", 16));
  }
  for (const Scene& scene : scenes) {
    MeshMedia media;
    media.update(scene);
    media.build_shapes();
    const MeshesView host = media.view();
    ASSERT_GT(host.count, 0);
    SceneResources resources;
    resources.update(scene);
    const RenderView view = resources.view(scene);
    DeviceCache cache(host_memory());
    const auto mirror_once = [&](const RenderView& as_of) {
      cache.begin_frame();
      DeviceMirror mirror(cache, as_of);
      const MeshesView d = mirror_meshes(mirror, host);
      cache.end_frame();
      return d;
    };
    cache.begin_frame();
    DeviceMirror mirror(cache, view);
    const MeshesView d = mirror_meshes(mirror, host);
    ASSERT_EQ(d.count, host.count);
    ASSERT_NE(d.objects, host.objects);
    ASSERT_NE(d.shapes, host.shapes);
    for (int m = 0; m < host.count; ++m) {
      const MeshMaterialView& h = host.objects[m];
      const MeshMaterialView& o = d.objects[m];
      for (const auto& [hd, od] : {std::pair{h.detail, o.detail}, std::pair{h.color_detail, o.color_detail}}) {
        if (hd.noise) {
          EXPECT_NE(hd.noise, od.noise);
        }
        if (hd.texture.data) {
          EXPECT_NE(hd.texture.data, od.texture.data);
        }
      }
      EXPECT_NE(o.tf.entries, h.tf.entries);
      EXPECT_NE(o.tf.sigma, h.tf.sigma);
      if (h.colored) {
        EXPECT_NE(o.color_tf.entries, h.color_tf.entries);
        EXPECT_NE(o.color_tf.sigma, h.color_tf.sigma);
      }
      // Every triangle of the mesh is mirrored (the count sizes the copy).
      EXPECT_EQ(std::size_t(host.shapes[m].triangle_count), media.world_meshes()[std::size_t(m)].triangles.size());
      EXPECT_NE(d.shapes[m].nodes, host.shapes[m].nodes);
      EXPECT_NE(d.shapes[m].triangles, host.shapes[m].triangles);
    }
    // The same media at points across the meshes' bounds, and the same
    // crossings along rays through them.
    const Box3 b = media.world_bounds();
    Pcg32 rng(7);
    const std::uint32_t all = (1u << host.count) - 1u;
    int crossings = 0;
    for (int i = 0; i < 500; ++i) {
      const vec3 p = b.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * b.extent();
      ASSERT_EQ(d.medium(all, p), host.medium(all, p)) << i;
      const vec3 dir = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
      const Ray ray{p - 2.0f * glm::length(b.extent()) * dir, dir};
      for (int m = 0; m < host.count; ++m) {
        float th[kMeshCrossings], td[kMeshCrossings];
        const int nh = host.shapes[m].crossings(ray, 0.0f, kInfinity, th, kMeshCrossings);
        ASSERT_EQ(d.shapes[m].crossings(ray, 0.0f, kInfinity, td, kMeshCrossings), nh);
        for (int k = 0; k < std::min(nh, kMeshCrossings); ++k) ASSERT_EQ(td[k], th[k]);
        crossings += nh;
      }
    }
    EXPECT_GT(crossings, 100);
    cache.end_frame();
    const std::uint64_t uploads = cache.uploads();
    EXPECT_GT(uploads, 0u);
    mirror_once(view);
    EXPECT_EQ(cache.uploads(), uploads) << "an unchanged scene uploads the meshes once";
    // A light, material, camera or render edit leaves the meshes' arrays;
    // a mesh, TF or data edit uploads them again.
    RenderView edited = view;
    edited.versions.lights += 1;
    edited.versions.material += 1;
    edited.versions.camera += 1;
    edited.versions.render += 1;
    edited.structures += 1;
    mirror_once(edited);
    EXPECT_EQ(cache.uploads(), uploads) << "a light or material edit uploads no mesh array";
    for (std::uint64_t SceneVersions::*part :
         {&SceneVersions::meshes, &SceneVersions::transfer_function, &SceneVersions::data}) {
      const std::uint64_t before = cache.uploads();
      edited.versions.*part += 1;
      mirror_once(edited);
      EXPECT_GT(cache.uploads(), before) << "an edit of the meshes, the TF or the data uploads them again";
    }
  }
}

// ---- on a CUDA device ----

bool have_gpu() { return cuda_built() && cuda_device_count() > 0; }

struct DeviceScene {
  std::string name;
  Scene scene;
};

std::vector<DeviceScene> device_scenes() {
  std::vector<DeviceScene> scenes;
  scenes.push_back({"spheres-floor", testing::with_floor(testing::lit_spheres(64))});
  const std::filesystem::path data = testing::shared_data_dir();
  if (std::filesystem::exists(data / "engine_256x256x128_uint8.nhdr")) {
    scenes.push_back({"engine-point", testing::repository_scene("scenes/engine-point.json", 96)});
  }
  if (std::filesystem::exists(data / "ct_head_cranium_256x256x108_int16.nhdr")) {
    scenes.push_back({"head-point", testing::repository_scene("scenes/head-point.json", 96)});
  }
  return scenes;
}

ParameterValues device_params(const TechniqueInfo& info) {
  ParameterValues params(info.parameters);
  ParameterSettings p;
  if (const ParameterSpec* r = info.parameters.find("resolution"); r && r->min <= 512.0 && 512.0 <= r->max) {
    p["resolution"] = 512.0;
  }
  if (info.name == "pathtrace") {
    p["spp"] = 16.0;
    p["min_spp"] = 4.0;
    p["progress"] = 0.0;
  }
  params.apply(p, true);
  return params;
}

// The settings each technique is checked with on the device: its defaults,
// and for occlusion-map also DVR mode (its grids: shadows per light, the AO
// grid, the planes'), with the AO per sample as well.
std::vector<std::pair<std::string, ParameterValues>> device_variants(const TechniqueInfo& info) {
  std::vector<std::pair<std::string, ParameterValues>> variants{{"", device_params(info)}};
  if (info.name == "occlusion-map") {
    ParameterValues dvr = device_params(info);
    dvr.set("mode", std::string("dvr"));
    variants.emplace_back(" (dvr)", dvr);
    dvr.set("dvr_ao", std::string("sample"));
    variants.emplace_back(" (dvr, AO per sample)", dvr);
  }
  return variants;
}

Image render_on(Device device, const Scene& scene, const TechniqueInfo& info, const ParameterValues& params,
                RenderStats& stats) {
  set_device_mode(device == Device::Cuda ? DeviceMode::Cuda : DeviceMode::Cpu);
  auto technique = info.create();
  technique->prepare(scene, params);
  Image image;
  technique->render(scene, image, &stats);
  return image;
}

// Both devices compute the same floats in a different order (FMA
// contraction on the GPU, other rounding of exp and pow), which moves a
// sample across an ERT or a depth threshold in a few pixels at most: RMSE
// 1e-3 linear is ten times the packet path's bound (packets_test.cpp) and
// far below one visible step; mean dE 0.05 with p99 0.5.
constexpr double kRmse = 1e-3;
constexpr double kMeanDe = 0.05;
constexpr double kP99De = 0.5;

TEST(CudaDevice, EveryTechniqueWithACudaPathMatchesTheCpu) {
  if (!have_gpu()) GTEST_SKIP() << "no CUDA device (or a build without the CUDA backend)";
  DeviceModeGuard guard;
  for (const DeviceScene& ds : device_scenes()) {
    for (const TechniqueInfo& info : technique_registry()) {
      // pathtrace's images are estimates: PathtraceAgreesWithinItsStandardError.
      if (!info.has_cuda_path || info.name == "pathtrace") continue;
      for (const auto& [variant, settings] : device_variants(info)) {
      for (bool cache : {false, true}) {
        ParameterValues params = settings;
        if (info.parameters.find("shadow_cache")) {
          params.set("shadow_cache", cache);
        } else if (cache) {
          continue;
        }
        SCOPED_TRACE(ds.name + " x " + info.name + variant + (cache ? " (cached)" : ""));
        RenderStats cpu_stats, gpu_stats;
        const Image cpu = render_on(Device::Cpu, ds.scene, info, params, cpu_stats);
        const Image gpu = render_on(Device::Cuda, ds.scene, info, params, gpu_stats);
        EXPECT_EQ(gpu_stats.device, Device::Cuda) << "the technique did not take its CUDA path";
        EXPECT_LE(rmse(gpu, cpu), kRmse);
        const DeltaEStats de = delta_e_stats(cpu, gpu);
        EXPECT_LE(de.mean, kMeanDe);
        EXPECT_LE(de.p99, kP99De);
        EXPECT_NEAR(double(gpu_stats.samples), double(cpu_stats.samples), 1e-3 * double(cpu_stats.samples));
      }
      }
    }
  }
}

// The same random streams on both devices: a path runs the same until a
// float comparison (a tentative collision, the roulette) falls the other way,
// after which it is an independent sample of the same estimator. So the
// images differ by at most the difference of two independent estimates,
// sqrt(2) times the standard error, even if every path diverged; a biased
// device path (a lost light, a wrong phase weight) is far outside that.
TEST(CudaDevice, PathtraceAgreesWithinItsStandardError) {
  if (!have_gpu()) GTEST_SKIP() << "no CUDA device (or a build without the CUDA backend)";
  DeviceModeGuard guard;
  const TechniqueInfo& info = find_technique("pathtrace");
  std::vector<DeviceScene> scenes = device_scenes();
  // Meshes as media (their BVHs and detail mirrored: backends/cuda/mesh_mirror.h).
  scenes.push_back({"mesh-sphere", testing::repository_scene("scenes/mesh-sphere.json", 64)});
  for (const DeviceScene& ds : scenes) {
    SCOPED_TRACE(ds.name);
    const ParameterValues params = device_params(info);
    set_device_mode(DeviceMode::Cpu);
    auto cpu_technique = info.create();
    cpu_technique->prepare(ds.scene, params);
    Image cpu;
    cpu_technique->render(ds.scene, cpu);
    const PathTraceEstimate* estimate = pathtrace_estimate(*cpu_technique);
    ASSERT_NE(estimate, nullptr);
    double error_squares = 0.0;
    for (std::size_t i = 0; i < estimate->standard_error.pixel_count(); ++i) {
      const vec4 e = estimate->standard_error.data()[i];
      error_squares += double(glm::dot(vec3(e), vec3(e))) / 3.0;
    }
    const double rms_error = std::sqrt(error_squares / double(estimate->standard_error.pixel_count()));
    RenderStats gpu_stats;
    const Image gpu = render_on(Device::Cuda, ds.scene, info, params, gpu_stats);
    EXPECT_EQ(gpu_stats.device, Device::Cuda);
    EXPECT_LE(rmse(gpu, cpu), 3.0 * std::sqrt(2.0) * rms_error + 1e-4);
    // The image means: the pixels' errors average down by sqrt(pixels).
    const double pixels = double(cpu.pixel_count());
    EXPECT_NEAR(testing::mean_rgb(gpu, 0, 0, gpu.width(), gpu.height()).g,
                testing::mean_rgb(cpu, 0, 0, cpu.width(), cpu.height()).g,
                3.0 * std::sqrt(2.0) * rms_error / std::sqrt(pixels) + 1e-5)
        << "the image means differ by more than their standard error";
  }
}

TEST(CudaDevice, LightMovesAndTfChangesMatchAFreshRender) {
  if (!have_gpu()) GTEST_SKIP() << "no CUDA device (or a build without the CUDA backend)";
  DeviceModeGuard guard;
  set_device_mode(DeviceMode::Cuda);
  const Scene scene = testing::repository_scene("scenes/engine-point.json", 96);
  Scene moved = scene;
  std::vector<Light> lights = moved.lights();
  lights[0].position += vec3(30.0f, -20.0f, 10.0f);
  lights[0].direction = glm::normalize(lights[0].direction + vec3(0.3f, 0.0f, 0.2f));
  moved.set_lights(lights);
  Scene edited = moved;
  TransferFunction tf = edited.transfer_function();
  tf.set_range(edited.tf_value_range() * vec2(1.2f, 0.9f));
  edited.set_transfer_function(tf);
  for (const TechniqueInfo& info : technique_registry()) {
    if (!info.has_cuda_path) continue;
    for (const auto& [variant, params] : device_variants(info)) {
      SCOPED_TRACE(info.name + variant);
      auto live = info.create();
      Image image;
      for (const Scene* s : std::initializer_list<const Scene*>{&scene, &moved, &edited}) {
        live->prepare(*s, params);
        live->render(*s, image);
        RenderStats stats;
        const Image fresh = render_on(Device::Cuda, *s, info, params, stats);
        EXPECT_EQ(rmse(image, fresh), 0.0) << "a stale device mirror";
      }
    }
  }
}

TEST(CudaDevice, AnUnchangedSceneUploadsNothing) {
  if (!have_gpu()) GTEST_SKIP() << "no CUDA device (or a build without the CUDA backend)";
  DeviceModeGuard guard;
  set_device_mode(DeviceMode::Cuda);
  const Scene scene = testing::repository_scene("scenes/engine-point.json", 64);
  for (const TechniqueInfo& info : technique_registry()) {
    if (!info.has_cuda_path) continue;
    SCOPED_TRACE(info.name);
    auto technique = info.create();
    const ParameterValues params = device_params(info);
    Image image;
    technique->prepare(scene, params);
    technique->render(scene, image);
    const std::uint64_t uploads = device_uploads();
    Scene turned = scene;
    Camera camera = turned.camera();
    camera.eye += vec3(5.0f, 0.0f, 0.0f);
    turned.set_camera(camera);
    for (const Scene* s : std::initializer_list<const Scene*>{&scene, &turned}) {
      technique->prepare(*s, params);
      technique->render(*s, image);
    }
    EXPECT_EQ(device_uploads(), uploads);
  }
}

TEST(CudaDevice, TooLittleDeviceMemoryIsAClearError) {
  if (!have_gpu()) GTEST_SKIP() << "no CUDA device (or a build without the CUDA backend)";
  DeviceModeGuard guard;
  set_device_mode(DeviceMode::Cuda);
  set_device_memory_budget_bytes(64 * 1024);
  const TechniqueInfo& info = find_technique("phong");
  auto technique = info.create();
  const Scene scene = testing::repository_scene("scenes/engine-point.json", 32);
  technique->prepare(scene, ParameterValues(info.parameters));
  Image image;
  try {
    technique->render(scene, image);
    FAIL() << "the engine CT fit in 64 KiB of device memory";
  } catch (const OutOfMemoryBudget& e) {
    EXPECT_NE(std::string(e.what()).find("device memory"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
