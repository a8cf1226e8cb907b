#include "penumbra/base/error.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/volume/procedural.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

// The key an InvalidScene names when parsing `text`, or "" when it parses.
std::string error_key(const std::string& text) {
  try {
    parse_scene(text, std::filesystem::temp_directory_path());
  } catch (const InvalidScene& e) {
    return e.key();
  }
  return "";
}

const char* kFull = R"({
  "version": 1,
  "volume": {"builtin": "spheres", "size": [16, 12, 10], "time_step": 0},
  "transfer_function": {"points": [[0, 0, 0, 0, 0], [1, 1, 0.5, 0.25, 0.8]], "range": [0, 1], "unit_length": 2.0,
                        "density_scale": 0.5},
  "shadow_transfer_function": {"points": [[0, 1, 1, 1, 0], [1, 1, 1, 1, 0.1]]},
  "camera": {"eye": [0, -50, 10], "target": [0, 0, 0], "up": [0, 0, 1], "fov_deg": 25, "projection": "orthographic",
             "height": 30},
  "lights": [{"type": "directional", "direction": [0, 0, -2], "color": [1, 0.9, 0.8], "intensity": 2},
             {"type": "point", "position": [5, 5, 5], "intensity": 100},
             {"type": "distant", "direction": [1, 0, -1], "angle_deg": 5, "profile": "gaussian"},
             {"type": "sphere", "position": [0, 0, 30], "radius": 2},
             {"type": "disk", "position": [0, 0, 30], "direction": [0, 0, -1], "radius": 3},
             {"type": "environment", "intensity": 0.5}],
  "material": {"albedo": 0.9, "phase_g": 0.3, "shading": "phong", "ambient": 0.05, "diffuse": 0.7, "specular": 0.1,
               "shininess": 30},
  "render": {"width": 64, "height": 48, "step": 0.25, "technique": "shadow-rays",
             "params": {"shadow_cache": true, "cache_resolution": 0.25, "pathtrace": {"mode": "single", "spp": 64}},
             "ert_threshold": 0.95, "jitter": true},
  "planes": [{"point": [0, 0, -10], "normal": [0, 0, 3], "color": [0.5, 0.5, 0.5]}],
  "clip_planes": [[0, 0, 2, 1]],
  "background": [0.1, 0.2, 0.3]
})";

TEST(SceneJson, ReadsEveryKey) {
  const Scene s = parse_scene(kFull, ".");
  EXPECT_EQ(s.volume().dims(), ivec3(16, 12, 10));
  EXPECT_EQ(s.transfer_function().points().size(), 2u);
  EXPECT_EQ(*s.transfer_function().range(), vec2(0.0f, 1.0f));
  EXPECT_FLOAT_EQ(*s.transfer_function().unit_length(), 2.0f);
  EXPECT_FLOAT_EQ(s.transfer_function().density_scale(), 0.5f);
  ASSERT_TRUE(s.shadow_transfer_function().has_value());
  EXPECT_FALSE(s.shadow_transfer_function()->range().has_value());  // "data"
  EXPECT_EQ(s.camera().projection, Projection::Orthographic);
  EXPECT_FLOAT_EQ(s.camera().ortho_height, 30.0f);
  ASSERT_EQ(s.lights().size(), 6u);
  EXPECT_FLOAT_EQ(s.lights()[0].direction.z, -1.0f);  // normalised
  EXPECT_EQ(s.lights()[1].type, LightType::Point);
  EXPECT_EQ(s.lights()[2].profile, LightProfile::Gaussian);
  EXPECT_FLOAT_EQ(s.lights()[3].radius, 2.0f);
  EXPECT_EQ(s.lights()[4].type, LightType::Disk);
  EXPECT_EQ(s.lights()[5].type, LightType::Environment);
  EXPECT_EQ(s.material().shading, Shading::Phong);
  EXPECT_FLOAT_EQ(s.material().shininess, 30.0f);
  EXPECT_EQ(s.render().width, 64);
  EXPECT_TRUE(s.render().jitter);
  EXPECT_EQ(std::get<bool>(s.render().params.at("shadow_cache")), true);
  // A technique's object becomes "technique.name" keys.
  EXPECT_EQ(std::get<std::string>(s.render().params.at("pathtrace.mode")), "single");
  EXPECT_EQ(std::get<double>(s.render().params.at("pathtrace.spp")), 64.0);
  EXPECT_FLOAT_EQ(s.planes()[0].normal.z, 1.0f);
  EXPECT_FLOAT_EQ(s.clip_planes()[0].w, 0.5f);
  EXPECT_EQ(s.background(), vec3(0.1f, 0.2f, 0.3f));
}

TEST(SceneJson, MissingKeysTakeTheDocumentedDefaults) {
  const Scene s = parse_scene(R"({"volume": {"builtin": "slab"}})", ".");
  EXPECT_EQ(s.volume().dims(), ivec3(64));
  EXPECT_FALSE(s.transfer_function().range().has_value());
  ASSERT_EQ(s.lights().size(), 1u);
  EXPECT_EQ(s.lights()[0].type, LightType::Directional);
  EXPECT_EQ(s.render().technique, "shadow-rays");
  EXPECT_FLOAT_EQ(s.render().step, 0.5f);
  EXPECT_FLOAT_EQ(s.material().ambient, 0.1f);
  EXPECT_TRUE(s.planes().empty());
  // The default camera frames the box.
  EXPECT_FLOAT_EQ(s.camera().target.x, 0.0f);
  EXPECT_GT(glm::length(s.camera().eye), 50.0f);
}

TEST(SceneJson, RoundTripsThroughWrite) {
  const Scene a = parse_scene(kFull, ".");
  const Scene b = parse_scene(write_scene_json(a), ".");
  EXPECT_EQ(b.volume().dims(), ivec3(16, 12, 10));
  ASSERT_EQ(b.lights().size(), a.lights().size());
  for (std::size_t i = 0; i < a.lights().size(); ++i) {
    EXPECT_EQ(b.lights()[i].type, a.lights()[i].type);
    EXPECT_LT(glm::distance(b.lights()[i].direction, a.lights()[i].direction), 1e-6f);  // re-normalised
    EXPECT_EQ(b.lights()[i].position, a.lights()[i].position);
    EXPECT_EQ(b.lights()[i].radius, a.lights()[i].radius);
    EXPECT_EQ(b.lights()[i].angle_deg, a.lights()[i].angle_deg);
  }
  EXPECT_EQ(b.transfer_function().points().size(), a.transfer_function().points().size());
  EXPECT_EQ(b.transfer_function().points()[1].color, a.transfer_function().points()[1].color);
  EXPECT_EQ(b.transfer_function().range(), a.transfer_function().range());
  EXPECT_TRUE(b.shadow_transfer_function().has_value());
  EXPECT_EQ(b.camera().eye, a.camera().eye);
  EXPECT_EQ(b.camera().projection, a.camera().projection);
  EXPECT_EQ(b.material().shininess, a.material().shininess);
  EXPECT_EQ(b.render().params, a.render().params);
  EXPECT_EQ(b.render().jitter, a.render().jitter);
  EXPECT_EQ(b.clip_planes(), a.clip_planes());
  EXPECT_EQ(b.planes()[0].point, a.planes()[0].point);
  EXPECT_EQ(b.background(), a.background());
  // Floats are written in their shortest form, not as widened doubles.
  EXPECT_NE(write_scene_json(a).find("0.1,"), std::string::npos);
  EXPECT_EQ(write_scene_json(a).find("0.10000000149"), std::string::npos);
}

TEST(SceneJson, ErrorsNameTheKey) {
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "colour": 1})"), "colour");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{}, {"type": "point", "colour": [1,1,1]}]})"),
            "lights[1].colour");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "render": {"width": "wide"}})"), "render.width");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "render": {"width": 0}})"), "render.width");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "render": {"params": {"cssm.k": 3}}})"),
            "render.params.cssm.k");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "render": {"params": {"cssm": {"k": {"x": 1}}}}})"),
            "render.params.cssm.k");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "render": {"params": {"cssm": {"k": [1]}}}})"),
            "render.params.cssm.k");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "camera": {"fov_deg": 200}})"), "camera.fov_deg");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "point"}]})"), "lights[0].position");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "laser"}]})"), "lights[0].type");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "point", "position": [0,0,0],
            "direction": [0,0,1]}]})"), "lights[0].direction");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"direction": [0,0,0]}]})"), "lights[0].direction");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "transfer_function": {"points": [[0, 1, 1, 1]]}})"),
            "transfer_function.points[0]");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "transfer_function": {"range": [1, 0]}})"),
            "transfer_function.range");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "teapot"}})"), "volume.builtin");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres", "size": [1, 8, 8]}})"), "volume.size");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres", "time_step": 3}})"), "volume.time_step");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres", "file": "x.nrrd"}})"), "volume");
  EXPECT_EQ(error_key(R"({"lights": []})"), "volume");
  EXPECT_EQ(error_key(R"({"version": 2, "volume": {"builtin": "spheres"}})"), "version");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "clip_planes": [[0, 0, 0, 1]]})"), "clip_planes[0]");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "material": {"shading": "toon"}})"), "material.shading");
  EXPECT_EQ(error_key(R"({"volume": )"), "(root)");
  EXPECT_EQ(error_key(R"([1, 2])"), "(root)");
}

// Distant gaussian lights take an optional second spread and a rotation of
// their frame; unset, the light is isotropic (angle_y_deg = angle_deg) and
// round trips without the keys. Other lights, and uniform cones, reject them.
TEST(SceneJson, AnisotropicGaussianLightsReadWriteAndValidate) {
  const Scene a = parse_scene(R"({"volume": {"builtin": "spheres"}, "lights": [
      {"type": "distant", "profile": "gaussian", "direction": [0, 0, -1], "angle_deg": 0, "angle_y_deg": 20,
       "rotation_deg": -70},
      {"type": "distant", "profile": "gaussian", "direction": [0, 0, -1], "angle_deg": 6}]})", ".");
  ASSERT_EQ(a.lights().size(), 2u);
  EXPECT_EQ(a.lights()[0].angle_y_deg, 20.0f);
  EXPECT_EQ(a.lights()[0].spread_y_deg(), 20.0f);
  EXPECT_EQ(a.lights()[0].rotation_deg, -70.0f);
  EXPECT_LT(a.lights()[1].angle_y_deg, 0.0f);  // unset
  EXPECT_EQ(a.lights()[1].spread_y_deg(), 6.0f);
  EXPECT_EQ(a.lights()[1].rotation_deg, 0.0f);
  const std::string text = write_scene_json(a);
  EXPECT_EQ(text.find("angle_y_deg"), text.rfind("angle_y_deg"));  // written for the first light only
  const Scene b = parse_scene(text, ".");
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(b.lights()[i].angle_y_deg, a.lights()[i].angle_y_deg);
    EXPECT_EQ(b.lights()[i].rotation_deg, a.lights()[i].rotation_deg);
  }
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "distant", "angle_deg": 5,
            "angle_y_deg": 3}]})"), "lights[0].angle_y_deg");  // uniform profile
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "distant", "rotation_deg": 3}]})"),
            "lights[0].rotation_deg");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"rotation_deg": 3}]})"),
            "lights[0].rotation_deg");  // directional
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "distant", "profile": "gaussian",
            "angle_y_deg": -1}]})"), "lights[0].angle_y_deg");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "lights": [{"type": "distant", "profile": "gaussian",
            "angle_y_deg": 90}]})"), "lights[0].angle_y_deg");
  // The same checks guard lights set from code.
  Scene c = a;
  std::vector<Light> lights = a.lights();
  lights[1].profile = LightProfile::Uniform;
  lights[1].angle_y_deg = 3.0f;
  try {
    c.set_lights(lights);
    ADD_FAILURE() << "a uniform light with angle_y_deg was accepted";
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "lights[1].angle_y_deg");
  }
  lights[1].angle_y_deg = -1.0f;
  lights[1].rotation_deg = 10.0f;
  try {
    c.set_lights(lights);
    ADD_FAILURE() << "a uniform light with rotation_deg was accepted";
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "lights[1].rotation_deg");
  }
}

TEST(SceneJson, TransferFunctionsCanComeFromParaViewPresets) {
  const auto dir = std::filesystem::temp_directory_path() / "penumbra_scene_json_preset";
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "presets.json");
    out << R"([{"Name": "Ramp", "RGBPoints": [0, 0, 0, 0, 10, 1, 0.5, 1], "Points": [0, 0, 0.5, 0, 10, 0.6, 0.5, 0]}])";
  }
  const Scene s = parse_scene(R"({"volume": {"builtin": "spheres"},
      "transfer_function": {"preset": {"file": "presets.json", "name": "Ramp"}, "range": [0, 1]}})", dir);
  EXPECT_NEAR(s.transfer_function().evaluate(1.0f).a, 0.6f, 1e-6f);
  EXPECT_NEAR(s.transfer_function().evaluate(1.0f).g, 0.21404f, 1e-4f);  // sRGB 0.5 decoded to linear
  EXPECT_EQ(*s.transfer_function().range(), vec2(0.0f, 1.0f));
  EXPECT_THROW(parse_scene(R"({"volume": {"builtin": "spheres"},
      "transfer_function": {"preset": {"file": "presets.json", "name": "Nope"}}})", dir), IoError);
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "transfer_function": {"preset": {"name": "x"}}})"),
            "transfer_function.preset.file");
  EXPECT_EQ(error_key(R"({"volume": {"builtin": "spheres"}, "transfer_function": {"preset": {"file": "a"},
      "points": [[0, 1, 1, 1, 1]]}})"), "transfer_function");
}

TEST(SceneJson, CallersCanLoadVolumesThemselves) {
  SceneParseOptions options;
  int calls = 0;
  auto shared = make_procedural_volume("spheres", ivec3(12));
  options.load_volume = [&](const VolumeSource& source, const std::filesystem::path& resolved) {
    ++calls;
    EXPECT_EQ(source.file, "data/x.nrrd");
    EXPECT_EQ(resolved, std::filesystem::path("/base/data/x.nrrd"));
    return shared;
  };
  options.allow_preset_files = false;
  const Scene s = parse_scene(R"({"volume": {"file": "data/x.nrrd"}})", "/base", options);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(s.volume_ptr(), shared);
  EXPECT_EQ(s.volume_source().file, "data/x.nrrd");
  EXPECT_FLOAT_EQ(s.camera().target.x, 0.0f);  // the default camera frames the loaded volume
  try {
    parse_scene(R"({"volume": {"file": "data/x.nrrd"}, "transfer_function": {"preset": {"file": "p.json"}}})", "/base",
                options);
    FAIL();
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "transfer_function.preset");
  }
}

TEST(SceneJson, MissingFilesAreIoErrorsNamingThePath) {
  try {
    parse_scene(R"({"volume": {"file": "no_such_volume.nrrd"}})", "/tmp");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(e.path().find("no_such_volume.nrrd"), std::string::npos);
  }
  EXPECT_THROW(load_scene("/tmp/penumbra_no_such_scene.json"), IoError);
}

TEST(SceneJson, RelativeVolumePathsAreRelativeToTheSceneFile) {
#ifdef PENUMBRA_SHARED_DATA_DIR
  const std::filesystem::path data(PENUMBRA_SHARED_DATA_DIR);
  if (!std::filesystem::exists(data / "bucky_32x32x32_uint8.nhdr")) GTEST_SKIP() << "no ../shared/data";
  const Scene s = parse_scene(R"({"volume": {"file": "bucky_32x32x32_uint8.nhdr", "spacing": [2, 2, 2]}})", data);
  EXPECT_EQ(s.volume().dims(), ivec3(32));
  EXPECT_FLOAT_EQ(s.volume().world_box().upper.x, 31.0f);  // re-centred with the new spacing
#else
  GTEST_SKIP();
#endif
}

// nlohmann reports a number beyond a double (1e400) as out_of_range, not as
// a parse_error: it is still the user's JSON at fault.
TEST(SceneJson, NumbersBeyondADoubleAreInvalidScenes) {
  try {
    parse_scene(R"({"volume": {"builtin": "spheres"}, "camera": {"fov_deg": 1e400}})", ".");
    ADD_FAILURE() << "1e400 accepted";
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "(root)");
    EXPECT_NE(std::string(e.what()).find("1e400"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
