#include "penumbra/base/error.h"
#include "penumbra/scene/scene.h"
#include "penumbra/volume/procedural.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(Scene, EachSetterBumpsOnlyItsOwnVersion) {
  Scene scene;
  scene.set_volume(make_procedural_volume("spheres", ivec3(8)));
  SceneVersions before = scene.versions();
  scene.set_camera(Camera{});
  EXPECT_NE(scene.versions().camera, before.camera);
  EXPECT_EQ(scene.versions().data, before.data);
  EXPECT_EQ(scene.versions().lights, before.lights);
  before = scene.versions();
  scene.set_lights({Light{}});
  EXPECT_NE(scene.versions().lights, before.lights);
  EXPECT_EQ(scene.versions().transfer_function, before.transfer_function);
  before = scene.versions();
  scene.set_transfer_function(TransferFunction{});
  EXPECT_NE(scene.versions().transfer_function, before.transfer_function);
  before = scene.versions();
  scene.set_planes({Plane{}});
  EXPECT_NE(scene.versions().geometry, before.geometry);
  before = scene.versions();
  scene.set_clip_planes({vec4(0, 0, 2, 1)});
  EXPECT_NE(scene.versions().geometry, before.geometry);
  EXPECT_FLOAT_EQ(scene.clip_planes()[0].z, 1.0f);  // normalised to world distances
  EXPECT_FLOAT_EQ(scene.clip_planes()[0].w, 0.5f);
}

TEST(Scene, TimeStepsChangeTheDataVersion) {
  auto v = std::make_shared<Volume>(ivec3(4), VoxelType::UInt8, 3);
  for (int f = 0; f < 3; ++f) std::fill_n(v->frame_as<std::uint8_t>(f), 64, std::uint8_t(f * 10));
  Scene scene;
  scene.set_volume(v, 1);
  const auto data = scene.versions().data;
  scene.set_time_step(2);
  EXPECT_NE(scene.versions().data, data);
  EXPECT_FLOAT_EQ(scene.volume_view().voxel(ivec3(0)), 20.0f);
  try {
    scene.set_time_step(3);
    FAIL();
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "volume.time_step");
  }
}

TEST(Scene, ValidationNamesTheOffendingKey) {
  Scene scene;
  Light bad;
  bad.direction = vec3(0.0f);
  try {
    scene.set_lights({Light{}, bad});
    FAIL();
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "lights[1].direction");
  }
  Material m;
  m.phase_g = 1.0f;
  EXPECT_THROW(scene.set_material(m), InvalidScene);
  RenderSettings r;
  r.width = 0;
  EXPECT_THROW(scene.set_render(r), InvalidScene);
  EXPECT_THROW(scene.volume(), InvalidScene);  // no volume yet
}

TEST(Scene, DerivedLengthsUseTheSmallestSpacing) {
  auto v = make_procedural_volume("slab", ivec3(8));
  v->set_spacing(vec3(0.5f, 2.0f, 1.0f));
  Scene scene;
  scene.set_volume(v);
  RenderSettings r;
  r.step = 0.5f;
  scene.set_render(r);
  EXPECT_FLOAT_EQ(scene.unit_length(), 0.5f);
  EXPECT_FLOAT_EQ(scene.step_world(), 0.25f);
  EXPECT_EQ(scene.tf_value_range(), vec2(1.0f, 2.0f));  // constant data: widened to [min, min + 1]
}

}  // namespace
}  // namespace penumbra
