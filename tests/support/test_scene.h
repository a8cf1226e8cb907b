#pragma once
// Small scenes for tests: a procedural volume, an explicit TF range and a
// camera framing the box, rendered at a small size.
#include "penumbra/render/image.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/scene/scene.h"
#include "penumbra/volume/procedural.h"

#include <filesystem>
#include <string>

namespace penumbra::testing {

// A scene over a procedural volume with a TF over [0, 1], a camera framing the
// box from -y, no lights and the given image size.
Scene procedural_scene(const std::string& builtin, ivec3 size, int image_size = 48);

// A TF with constant colour and the given alpha for every value in [lo, 1]
// and alpha 0 below lo.
TransferFunction step_tf(float lo, vec3 color, float alpha);

// A unit-intensity directional light travelling along `direction`
// (normalised), and a unit-intensity point light at `position`.
Light directional_light(vec3 direction);
Light point_light(vec3 position);

// The 48^3 spheres with a translucent orange-to-white TF, one directional
// light from the upper front and a little ambient.
Scene lit_spheres(int image_size = 48);

// The scene with an opaque grey floor plane 8 units below the volume's box.
Scene with_floor(Scene scene);

// Writes the image as PNG into $PENUMBRA_TEST_IMAGES when that is set, so a
// developer can look at what a test rendered.
void save_test_image(const Image& image, const std::string& name);

// A scene file of the repository (path relative to its root, e.g.
// "scenes/plate-over-plane.json"), rendered at image_size^2.
// The checkout and ../shared/data (PENUMBRA_TEST_SOURCE_DIR and
// PENUMBRA_TEST_SHARED_DATA_DIR override them for a bundled test binary).
std::filesystem::path source_dir();
std::filesystem::path shared_data_dir();

Scene repository_scene(const std::string& relative_path, int image_size);

// Renders with a registered technique and parameters (name=value pairs);
// the render's statistics into `stats` when given.
Image render_with(const Scene& scene, const std::string& technique, const ParameterSettings& params = {},
                  RenderStats* stats = nullptr);

// A built-in mesh scaled by `scale`, filled with a homogeneous medium:
// constant detail through a TF of `color` and `alpha` per world unit, no
// highlight.
MeshObject homogeneous_mesh(const std::string& builtin, int resolution, float scale, vec3 color, float alpha);

// An orthographic camera at `eye` looking at the origin, `height` world units tall.
Camera orthographic_camera(vec3 eye, float height, vec3 up = vec3(0.0f, 1.0f, 0.0f));

// Mean of an image's rgb over a pixel rectangle [x0, x1) x [y0, y1).
vec3 mean_rgb(const Image& image, int x0, int y0, int x1, int y1);

// Mean CIEDE2000 between two images of the same size.
double mean_de(const Image& a, const Image& b);

// An antialiased solid's density at a signed distance from its surface: 1
// inside, 0 outside, a one-voxel linear ramp across the boundary.
float antialiased_solid(float signed_distance);

}  // namespace penumbra::testing
