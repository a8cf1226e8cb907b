// A mesh coloured by one detail function and made opaque by another (Patel et
// al. 2013, Fig. 9: a 3D texture for colour, a procedural function for
// opacity), in convolution and in the path tracer, which share the medium
// (MeshMaterialView::medium).
#include "penumbra/scene/mesh_shapes.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// A box mesh filling x, y, z in [-12, 12] of an empty 32^3 frame, seen from
// +z by an orthographic camera. Opacity: constant detail through a TF of
// alpha 0.2 per unit. Colour (when `colored`): a 2x1x1 texture, 0 at x = -12
// and 1 at x = +12 (texel centres on the mesh's bounds), through a TF from red
// to blue.
Scene two_function_box(bool colored, bool lit) {
  Scene scene = procedural_scene("empty", ivec3(32), 32);
  TransferFunction clear({{0.0f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.0f}});
  scene.set_transfer_function(clear);
  scene.set_camera(testing::orthographic_camera(vec3(0.0f, 0.0f, 100.0f), 32.0f));
  if (lit) {
    scene.set_lights({testing::directional_light(vec3(0.0f, 0.0f, -1.0f))});
  } else {
    scene.set_lights({});
  }
  Material mat;
  mat.ambient = lit ? 0.0f : 1.0f;
  scene.set_material(mat);
  MeshObject m = testing::homogeneous_mesh("box", 1, 12.0f, vec3(1.0f), 0.2f);
  if (colored) {
    auto texture = std::make_shared<Volume>(ivec3(2, 1, 1), VoxelType::Float32);
    texture->frame_as<float>(0)[0] = 0.0f;
    texture->frame_as<float>(0)[1] = 1.0f;
    m.material.has_color_detail = true;
    m.material.color_detail.type = DetailType::Texture;
    m.material.color_detail.texture = texture;
    m.material.color_detail.texture_file = "ramp.nrrd";
    m.material.color_tf = TransferFunction({{0.0f, vec3(1.0f, 0.0f, 0.0f), 0.0f}, {1.0f, vec3(0.0f, 0.0f, 1.0f), 0.0f}});
  }
  scene.set_meshes({m});
  return scene;
}

// World x of a pixel column's centre (32 px over 32 units).
float column_x(int x) { return float(x) + 0.5f - 16.0f; }

void expect_colour_ramp(const Image& colored, const Image& plain, float tolerance, const char* what) {
  int checked = 0;
  for (int y = 6; y < 26; ++y) {
    for (int x = 6; x < 26; ++x) {
      const vec4 c = colored.at(x, y), p = plain.at(x, y);
      EXPECT_NEAR(c.a, p.a, 0.02f) << what << ": the opacity is the opacity detail's";
      // Albedo (1 - u, 0, u) at u = (x + 12) / 24, times what the white box gets.
      const float u = (column_x(x) + 12.0f) / 24.0f;
      EXPECT_NEAR(c.r, (1.0f - u) * p.r, tolerance) << what << " x " << x;
      EXPECT_NEAR(c.b, u * p.b, tolerance) << what << " x " << x;
      EXPECT_NEAR(c.g, 0.0f, tolerance) << what << " x " << x;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 400);
}

TEST(MeshColorDetail, ColourFromOneFunctionOpacityFromTheOther) {
  // convolution, ambient light only: exact up to the texture's trilinear ramp.
  expect_colour_ramp(render_with(two_function_box(true, false), "convolution"),
                     render_with(two_function_box(false, false), "convolution"), 0.01f, "convolution");
  // The path tracer, lit from the camera: the same ramp within its noise
  // (256 paths of single scattering, the white box's radiance about 0.24).
  const ParameterSettings paths{{"spp", 256.0}, {"mode", std::string("single")}, {"progress", false}};
  expect_colour_ramp(render_with(two_function_box(true, true), "pathtrace", paths),
                     render_with(two_function_box(false, true), "pathtrace", paths), 0.03f, "pathtrace");
}

}  // namespace
}  // namespace penumbra
