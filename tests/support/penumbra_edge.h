#pragma once
// The sharp-edge soft-shadow experiment (issue 18): a thin opaque half-plane
// (x < edge_x, the full y extent) `distance` world units above a white floor,
// lit straight down by one light, seen from above with an orthographic
// camera. The viewing TF is transparent and only the shadow TF is opaque, so
// a floor pixel is exactly the light's visibility V (ambient 0, cosine 1,
// unit radiance); penumbra_width_10_90 measures where V rises from 10 % to
// 90 % across the edge.
#include "penumbra/render/image.h"
#include "penumbra/scene/scene.h"

namespace penumbra::testing {

struct EdgeScene {
  Scene scene;
  float edge_x = 0.0f;      // world x of the occluder's edge
  float distance = 0.0f;    // from the occluder's mid-plane to the floor
  float pixel_size = 0.0f;  // world units per pixel on the floor
};

// `light` has its direction replaced by straight down (0, 0, -1) and, for a
// sphere or disk, its position set `light_height` above the occluder.
EdgeScene edge_scene(Light light, float distance, int image_size = 64, float view_width = 32.0f,
                     float light_height = 0.0f);

// 10-90 % width of the floor's visibility profile across x (rows averaged,
// divided by the same scene rendered without shadows, crossings interpolated
// linearly), in world units; -1e9 scaled when a level is never crossed.
float penumbra_width_10_90(const EdgeScene& edge, const Image& image, const Image& unshadowed);

// The edge scene's floor without shadows (shadow-rays, shadow density 0): the
// divisor above, the same unshadowed lighting for every technique.
Image unshadowed_floor(const EdgeScene& edge);

// A distant light straight down of the given angle_deg and profile (the edge
// scene replaces its direction anyway).
Light distant_light(float angle_deg, LightProfile profile = LightProfile::Uniform);

// `light` as a distant light of the given angular radius (scene/light.h's
// angle_deg), keeping its direction, colour and intensity.
Light as_distant(Light light, float angle_deg);

// A technique's softness knob (issue 18): unset (absent from `common`) it
// follows the light `sized`, the same image as the knob set to `matching`;
// set to `other` it overrides the light's size (the same image as the
// sizeless `plain` light, a directional one, with the knob at `other`); and
// `plain` with the knob unset equals the knob at `plain_default`.
// Returns the image of `sized` with the knob at `other`.
Image expect_knob_overrides_light(const Scene& scene, const std::string& technique, const ParameterSettings& common,
                                  const std::string& knob, const Light& sized, double matching, const Light& plain,
                                  double plain_default, double other);

}  // namespace penumbra::testing
