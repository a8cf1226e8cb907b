// The scene x technique matrix: every registered technique on several
// procedural scenes gives finite, bounded, non-blank images; and exact
// relations between techniques, compared through metrics; and that a live
// technique, after edits to the scene or its parameters, renders what a
// fresh one does.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

struct MatrixScene {
  const char* name;
  Scene (*make)();
};

Scene with_light(Scene scene, LightType type) {
  Light l;
  l.type = type;
  l.direction = glm::normalize(vec3(0.3f, 0.6f, -1.0f));
  l.position = vec3(10.0f, -30.0f, 40.0f);
  l.intensity = type == LightType::Point ? 2500.0f : 1.0f;
  scene.set_lights({l});
  return scene;
}

const MatrixScene kScenes[] = {
    {"spheres-directional-floor",
     [] {
       Scene s = with_light(procedural_scene("spheres", ivec3(32), 24), LightType::Directional);
       s.set_transfer_function(testing::step_tf(0.2f, vec3(0.9f, 0.6f, 0.3f), 0.4f));
       s.set_planes({Plane{vec3(0.0f, 0.0f, -25.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
       return s;
     }},
    {"shell-point",
     [] {
       Scene s = with_light(procedural_scene("shell", ivec3(32), 24), LightType::Point);
       s.set_transfer_function(TransferFunction({{0.0f, vec3(1.0f), 0.0f}, {0.4f, vec3(1.0f, 0.2f, 0.1f), 0.1f},
                                                 {0.6f, vec3(1.0f, 0.2f, 0.1f), 0.1f}, {1.0f, vec3(1.0f), 1.0f}}));
       TransferFunction tf = s.transfer_function();
       tf.set_range(vec2(0.0f, 1.0f));
       s.set_transfer_function(tf);
       return s;
     }},
    {"marschner-lobb-phong-clipped",
     [] {
       Scene s = with_light(procedural_scene("marschner-lobb", ivec3(32), 24), LightType::Directional);
       s.set_transfer_function(testing::step_tf(0.5f, vec3(0.7f, 0.8f, 1.0f), 0.6f));
       Material m;
       m.shading = Shading::Phong;
       s.set_material(m);
       s.set_clip_planes({vec4(0.3f, 0.0f, 1.0f, 2.0f)});
       return s;
     }},
    {"edge-point-light-inside",
     [] {
       Scene s = with_light(procedural_scene("edge", ivec3(32), 24), LightType::Point);
       Light l = s.lights()[0];
       l.position = vec3(0.0f, 0.0f, 14.0f);
       l.intensity = 100.0f;
       s.set_lights({l});
       s.set_transfer_function(testing::step_tf(0.5f, vec3(1.0f), 0.9f));
       return s;
     }},
};

TEST(TechniqueMatrix, EveryTechniqueRendersEveryScene) {
  for (const MatrixScene& ms : kScenes) {
    const Scene scene = ms.make();
    for (const TechniqueInfo& info : technique_registry()) {
      SCOPED_TRACE(std::string(ms.name) + " x " + info.name);
      auto t = info.create();
      const ParameterValues params(info.parameters);
      t->prepare(scene, params);
      const auto rebuilds = t->rebuilds();
      t->prepare(scene, params);
      EXPECT_EQ(t->rebuilds(), rebuilds) << "prepare without changes must not rebuild";
      Image image;
      RenderStats stats;
      t->render(scene, image, &stats);
      ASSERT_EQ(image.width(), 24);
      float lo = 1e30f, hi = -1e30f;
      for (const vec4& p : image.pixels()) {
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c]));
        ASSERT_GE(p.a, 0.0f);
        ASSERT_LE(p.a, 1.0f + 1e-6f);
        lo = std::min(lo, luminance(vec3(p)));
        hi = std::max(hi, luminance(vec3(p)));
      }
      EXPECT_GE(lo, 0.0f);
      EXPECT_LT(hi, 50.0f);
      EXPECT_GT(hi - lo, 1e-3f) << "blank image";
      EXPECT_GT(stats.samples, 0u);
    }
  }
}

// A technique's defaults, with smaller shadow maps and fewer paths, for time.
ParameterValues quick_parameters(const TechniqueInfo& info) {
  ParameterValues params(info.parameters);
  if (const ParameterSpec* r = info.parameters.find("resolution"); r && r->min <= 256.0 && 256.0 <= r->max) {
    params.apply({{"resolution", 256.0}}, true);
  }
  if (info.name == "pathtrace") params.apply({{"spp", 8.0}, {"min_spp", 4.0}, {"progress", false}}, true);
  return params;
}

// Interactive edits give the image of a fresh technique. A technique keeps
// structures from frame to frame (shadow caches, moment pyramids, light
// buffers, per-pixel buffers), and each must follow what it depends on and
// nothing else may leak from the frame before. On each matrix scene every
// technique renders once, then after each edit (camera orbit, light move, TF
// change, image size, material, a second light, a clip plane, planes added or
// removed, the render step, a shadow TF, another volume, a larger image)
// prepares and renders again; the image must be that of a new instance
// prepared on the edited scene.
struct SceneEdit {
  const char* name;
  std::function<void(Scene&)> apply;
};

// Renders `scene` with a live instance of `info`, then again after each edit
// in turn, each time against a fresh instance prepared on the edited scene.
// Most edits must change the image (else they test nothing).
void expect_edits_give_a_fresh_image(const TechniqueInfo& info, Scene scene, const std::vector<SceneEdit>& edits,
                                     const std::string& label) {
  const ParameterValues params = quick_parameters(info);
  auto live = info.create();
  live->prepare(scene, params);
  Image image, before;
  live->render(scene, image);
  int changed = 0;
  for (const SceneEdit& edit : edits) {
    SCOPED_TRACE(label + " x " + info.name + ", after the " + edit.name);
    before = image;
    edit.apply(scene);
    live->prepare(scene, params);
    live->render(scene, image);
    auto fresh = info.create();
    fresh->prepare(scene, params);
    Image expected;
    fresh->render(scene, expected);
    ASSERT_EQ(image.width(), expected.width());
    ASSERT_EQ(image.height(), expected.height());
    EXPECT_LE(max_abs_error(image, expected), 1e-6);
    changed += int(image.width() != before.width() || image.height() != before.height() ||
                   max_abs_error(image, before) > 1e-3);
  }
  EXPECT_GE(2 * changed, int(edits.size())) << label << " x " << info.name << ": edits that changed the image";
}

// The edit that sets the image to width x height.
std::function<void(Scene&)> resize_image(int width, int height) {
  return [width, height](Scene& s) {
    RenderSettings r = s.render();
    r.width = width;
    r.height = height;
    s.set_render(r);
  };
}

class SceneEdits : public ::testing::TestWithParam<int> {};

TEST_P(SceneEdits, GiveTheImageOfAFreshTechnique) {
  const std::vector<SceneEdit> edits = {
      {"camera orbit",
       [](Scene& s) {
         Camera c = s.camera();
         c.orbit(35.0f, 10.0f);
         s.set_camera(c);
       }},
      {"light move",
       [](Scene& s) {
         Light l = s.lights()[0];
         l.direction = glm::normalize(vec3(-0.5f, 0.4f, -0.8f));
         l.position += vec3(-20.0f, 15.0f, 5.0f);
         s.set_lights({l});
       }},
      {"TF change",
       [](Scene& s) {
         TransferFunction tf = testing::step_tf(0.35f, vec3(0.5f, 0.8f, 0.9f), 0.25f);
         s.set_transfer_function(tf);
       }},
      {"image size", resize_image(20, 28)},
      {"material",
       [](Scene& s) {
         Material m = s.material();
         m.ambient = 0.3f;
         m.shading = m.shading == Shading::Phong ? Shading::Phase : Shading::Phong;
         s.set_material(m);
       }},
      {"second light",
       [](Scene& s) {
         std::vector<Light> lights = s.lights();
         Light l;
         l.type = LightType::Point;
         l.position = vec3(-25.0f, 30.0f, 20.0f);
         l.intensity = 1500.0f;
         lights.push_back(l);
         s.set_lights(lights);
       }},
      {"clip plane",
       [](Scene& s) { s.set_clip_planes({vec4(-0.4f, 0.2f, 1.0f, 3.0f)}); }},
      {"planes",
       [](Scene& s) {
         if (s.planes().empty()) {
           s.set_planes({Plane{vec3(0.0f, 0.0f, -22.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.7f)}});
         } else {
           s.set_planes({});
         }
       }},
      {"render step",
       [](Scene& s) {
         RenderSettings r = s.render();
         r.step *= 1.6f;
         s.set_render(r);
       }},
      {"shadow TF",
       [](Scene& s) { s.set_shadow_transfer_function(testing::step_tf(0.5f, vec3(1.0f), 0.8f)); }},
      {"new volume",
       [](Scene& s) {
         s.set_volume(make_procedural_volume("marschner-lobb", ivec3(28, 34, 30)));
         s.set_camera(Camera::framing(s.volume().world_box()));
       }},
      {"larger image", resize_image(30, 26)},
  };
  const MatrixScene& ms = kScenes[GetParam()];
  for (const TechniqueInfo& info : technique_registry()) {
    expect_edits_give_a_fresh_image(info, ms.make(), edits, ms.name);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMatrixScene, SceneEdits, ::testing::Range(0, int(std::size(kScenes))),
                         [](const ::testing::TestParamInfo<int>& info) {
                           std::string name = kScenes[info.param].name;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The same for mesh scenes, with the techniques that draw meshes: the mesh
// moved, its material's TF and detail changed, its detail's time advanced
// (animation), a second mesh added, and the light and camera moved.
TEST(SceneEdits, OnMeshScenesGiveTheImageOfAFreshTechnique) {
  const std::vector<SceneEdit> edits = {
      {"mesh move",
       [](Scene& s) {
         std::vector<MeshObject> meshes = s.meshes();
         meshes[0].translate += vec3(4.0f, -3.0f, 2.0f);
         meshes[0].rotate_deg += vec3(0.0f, 0.0f, 30.0f);
         s.set_meshes(meshes);
       }},
      {"mesh TF",
       [](Scene& s) {
         std::vector<MeshObject> meshes = s.meshes();
         TransferFunction tf({{-1.0f, vec3(0.2f, 0.6f, 0.9f), 0.02f}, {1.0f, vec3(1.0f, 0.9f, 0.5f), 0.4f}});
         tf.set_range(vec2(-1.0f, 1.0f));
         meshes[0].material.tf = tf;
         s.set_meshes(meshes);
       }},
      {"detail frequency",
       [](Scene& s) {
         std::vector<MeshObject> meshes = s.meshes();
         meshes[0].material.detail.frequency *= 1.7f;
         s.set_meshes(meshes);
       }},
      {"detail time",
       [](Scene& s) {
         std::vector<MeshObject> meshes = s.meshes();
         meshes[0].material.detail.time_dependent = true;
         meshes[0].material.detail.fractal.time += 0.35f;
         s.set_meshes(meshes);
       }},
      {"second mesh",
       [](Scene& s) {
         std::vector<MeshObject> meshes = s.meshes();
         MeshObject other = meshes[0];
         other.scale *= 0.5f;
         other.translate += vec3(-18.0f, 6.0f, 4.0f);
         meshes.push_back(other);
         s.set_meshes(meshes);
       }},
      {"light move",
       [](Scene& s) {
         Light l = s.lights()[0];
         l.direction = glm::normalize(vec3(-0.4f, 0.5f, -0.75f));
         s.set_lights({l});
       }},
      {"camera orbit",
       [](Scene& s) {
         Camera c = s.camera();
         c.orbit(-40.0f, 5.0f);
         s.set_camera(c);
       }},
  };
  const Scene scene = testing::repository_scene("scenes/mesh-sphere.json", 24);
  for (const TechniqueInfo& info : technique_registry()) {
    if (info.draws_meshes) expect_edits_give_a_fresh_image(info, scene, edits, "mesh-sphere");
  }
}

// Other values of a parameter near `current`, to try in turn: a flag
// flipped, the next choice, a number a quarter larger or smaller, an integer
// one or two more, one less, doubled, or 16 (a size that must be 0 or at
// least 16; two more: an odd kernel size).
std::vector<ParameterValue> other_values(const ParameterSpec& spec, const ParameterValue& current) {
  switch (spec.type) {
    case ParameterType::Bool: return {!std::get<bool>(current)};
    case ParameterType::Choice: {
      const auto at = std::find(spec.choices.begin(), spec.choices.end(), std::get<std::string>(current));
      const std::size_t next = at == spec.choices.end() ? 0 : std::size_t(at - spec.choices.begin() + 1);
      return {spec.choices[next % spec.choices.size()]};
    }
    case ParameterType::Int: {
      const double v = std::get<double>(current);
      return {v + 1.0, v - 1.0, v + 2.0, 2.0 * v, 16.0};
    }
    case ParameterType::Float: {
      const double v = std::get<double>(current);
      return {v * 1.25, v * 0.8, spec.min + 0.1 * (spec.max - spec.min)};
    }
  }
  return {};
}

// Parameter edits, the same way: each parameter of every technique in turn
// set to another value (one the parameter and prepare() accept) and then back
// to the defaults; the live instance must render what a fresh one prepared
// with the same values renders.
TEST(ParameterEdits, GiveTheImageOfAFreshTechnique) {
  const Scene scene = kScenes[0].make();
  int edits = 0;
  for (const TechniqueInfo& info : technique_registry()) {
    const ParameterValues defaults = quick_parameters(info);
    auto live = info.create();
    live->prepare(scene, defaults);
    Image default_image, image;
    live->render(scene, default_image);
    for (const ParameterSpec& spec : info.parameters.specs()) {
      SCOPED_TRACE(info.name + "." + spec.name);
      // The first other value that the parameter and prepare() accept.
      ParameterValues edited = defaults;
      Image expected;
      bool found = false;
      for (const ParameterValue& value : other_values(spec, defaults.value(spec.name))) {
        edited = defaults;
        auto fresh = info.create();
        try {
          edited.set(spec.name, value);
          if (edited == defaults) continue;
          fresh->prepare(scene, edited);
          fresh->render(scene, expected);
        } catch (const Error&) {
          continue;  // a value or combination the technique refuses
        }
        found = true;
        break;
      }
      ASSERT_TRUE(found) << "no other value to try";
      live->prepare(scene, edited);
      live->render(scene, image);
      EXPECT_LE(max_abs_error(image, expected), 1e-6) << "edited";
      live->prepare(scene, defaults);
      live->render(scene, image);
      EXPECT_LE(max_abs_error(image, default_image), 1e-6) << "back to the defaults";
      ++edits;
    }
  }
  EXPECT_GE(edits, 100);
}

// With albedo 1, ambient 1 and no lights, lit single scattering reduces to
// emission-absorption: albedo * c * ambient = c.
TEST(TechniqueRelations, AmbientOnlyScatteringEqualsEmissionAbsorption) {
  Scene scene = procedural_scene("marschner-lobb", ivec3(32), 32);
  scene.set_transfer_function(testing::step_tf(0.4f, vec3(0.3f, 0.7f, 0.9f), 0.3f));
  scene.set_lights({});
  Material m;
  m.ambient = 1.0f;
  scene.set_material(m);
  const Image ea = render_with(scene, "emission-absorption");
  EXPECT_LT(rmse(ea, render_with(scene, "shadow-rays")), 1e-6);
  EXPECT_LT(rmse(ea, render_with(scene, "phong")), 1e-6);
}

// phong is shadow-rays with Phong shading and no shadows.
TEST(TechniqueRelations, PhongEqualsShadowRaysWithPhongShadingAndNoShadows) {
  Scene scene = with_light(procedural_scene("spheres", ivec3(32), 32), LightType::Directional);
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(0.8f), 0.5f));
  Material m;
  m.shading = Shading::Phong;
  scene.set_material(m);
  EXPECT_LT(rmse(render_with(scene, "phong"), render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}})),
            1e-6);
}

// Emission-absorption through a homogeneous slab seen head-on with an
// orthographic camera: every pixel is c (1 - e^(-sigma d)) + bg e^(-sigma d).
TEST(TechniqueRelations, EmissionAbsorptionOfASlabIsAnalytic) {
  Scene scene = procedural_scene("slab", ivec3(16, 20, 16), 16);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.2f, 0.5f, 1.0f), 0.1f));
  scene.set_background(vec3(1.0f, 0.0f, 0.0f));
  Camera camera;
  camera.eye = vec3(0.0f, -50.0f, 0.0f);
  camera.target = vec3(0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = 10.0f;
  scene.set_camera(camera);
  const Image image = render_with(scene, "emission-absorption");
  const float t = std::pow(0.9f, 19.0f);  // d = 19 voxels, alpha 0.1 per voxel
  for (const vec4& p : image.pixels()) {
    ASSERT_NEAR(p.r, 0.2f * (1.0f - t) + t, 1e-4f);
    ASSERT_NEAR(p.b, 1.0f - t, 1e-4f);
    ASSERT_NEAR(p.a, 1.0f - t, 1e-4f);
  }
}

// Phong on a sphere lit from the eye: the centre faces the light (n.l = 1)
// and the limb does not, so the centre is brighter.
TEST(TechniqueRelations, PhongShadesBySurfaceOrientation) {
  Scene scene = procedural_scene("shell", ivec3(48), 48);
  scene.set_transfer_function(testing::step_tf(0.9f, vec3(1.0f), 1.0f));  // the opaque core only
  Light l;
  l.direction = vec3(0.0f, 1.0f, 0.0f);  // travelling along the view direction
  scene.set_lights({l});
  Material m;
  m.shading = Shading::Phong;
  m.ambient = 0.0f;
  m.specular = 0.0f;
  scene.set_material(m);
  const Image image = render_with(scene, "phong");
  const float center = image.at(24, 24).r;
  EXPECT_NEAR(center, m.diffuse, 0.05f);
  // Find the limb along the middle row: the last lit pixel is much darker.
  int x = 24;
  while (x + 1 < 48 && image.at(x + 1, 24).a > 0.5f) ++x;
  EXPECT_LT(image.at(x, 24).r, 0.6f * center);
}

}  // namespace
}  // namespace penumbra
