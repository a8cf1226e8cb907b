#pragma once
// shadow-rays: single scattering with exact light visibility (DESIGN.md 1),
// the hard-shadow reference every soft-shadow technique is compared with.
// V_light(x) is the transmittance exp(-integral sigma_t) marched from x to
// the volume boundary (directional) or to the light (point), with the same
// step, clip planes and empty-space skipping as the viewing rays.
//
// With light_samples = n > 1 it is the deterministic soft-shadow reference
// for area lights (distant cones and Gaussians, spheres, disks): V_light(x)
// is the mean transmittance of n stratified, seeded shadow rays toward the
// light, drawn exactly as the path tracer draws its light samples
// (area_light_transmittance.h). The unshadowed term (phase function, the
// light's radiance) stays that of the light's centre, as for every other
// single-scattering technique, so against the path tracer's single
// scattering the only difference is that the phase function and a disk's
// cosine are not integrated over the light: relative error ~ (angle)^2, under
// 1 % for lights below 8 degrees. Opaque planes block the light as seen from
// its centre (all techniques do); volume occluders soften.
//
// The scene's closed meshes are media too (render/mesh_media.h): a mesh
// scene's viewing rays are marched through the volume and the meshes
// together (render/mesh_march.h) and every shadow ray crosses both, so each
// mesh scene has a hard-shadow reference; such scenes render on the CPU
// (render_meshes has no device launch). docs/shadow-rays.md, "Meshes".
//
// Default light_samples = 1: one ray toward the light's centre, the
// hard-shadow reference, unchanged images for every existing scene; ask for
// 16-64 samples for a soft-shadow reference (docs/PERFORMANCE.md
// "shadow-rays with light samples" measures error and time against the path
// tracer). Lights without an extent (directional, point, zero angle or
// radius) always take one ray.
//
// Parameters
//   shadow_density_scale  multiplies sigma_t along shadow rays only (0 = no
//                         shadows, i.e. unshadowed single scattering)
//   light_samples         shadow rays per light with an extent (1 = centre)
//   shadow_cache          precompute V per light on a grid (Ament et al. 2014,
//                         Algorithm 1, used with exact transmittance) and
//                         interpolate it instead of marching per sample
//   cache_resolution      cache grid size as a fraction of the data grid
//                         (with light_samples > 1 each texel holds the area
//                         mean, so the cache represents area lights)
// Passes
//   prepare: with the cache on, one transmittance volume per light, rebuilt
//            only when the data, TF, lights, clip planes or these parameters
//            change
//   render:  one ray-casting pass; per lit sample one shadow ray per light,
//            light_samples for an area light (or one cache lookup)
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo shadow_rays_info();

}  // namespace penumbra
