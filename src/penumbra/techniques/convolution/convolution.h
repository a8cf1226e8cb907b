#pragma once
// convolution: D. Patel, V. Soltészová, J. M. Nordbotten and S. Bruckner,
// "Instant Convolution Shadows for Volumetric Detail Mapping", ACM TOG 32(5),
// 2013. View-aligned slabs are traversed front to back; each slab is both
// occluder and receiver, and light travels from slab to slab by a 2D
// convolution of one pair of ping-pong buffers per light. Iterating a kernel
// of mean e mu and covariance d1 e Sigma (eq. 7/15) gives, by the central
// limit theorem, the exact shadow of a distant Gaussian light (mean mu,
// covariance Sigma on the virtual light plane) for occluder-receiver pairs
// d1 apart, and the correct half-shadow line behind an edge at any distance.
// Light model and the mapping from the scene's lights: gaussian_light.h.
//
// Parameters
//   slab_distance       e in voxels (0: automatic, Patel et al. section 7:
//                       the render step where the volume has extinction, at
//                       most half the finest detail feature of the meshes
//                       (lattice cell of the highest octave, or texel), at
//                       most 4096 slabs)
//   optimal_distance    d1 in voxels (0: a quarter of the box's depth extent)
//   kernel              gaussian | poisson | ellipse (slab_kernel.h)
//   kernel_samples      taps (ellipse N, default 2; poisson N, default 8;
//                       gaussian M per side, default 19), 0 = default
//   light_sigma_x2, light_sigma_y2, light_rotation_deg
//                       the paper's (sigma_x^2, sigma_y^2, alpha) for every
//                       light (sigma_x2 < 0: from the scene's lights)
//   seed                for the random kernel rotations
//   preintegrated       preintegrated compositing of the volume (Fig. 19)
//   guard_band          light buffers over a band around the image
//   carried_light       zero-variance lights also carried along their rays
//                       across empty space (carried_light.h; off: re-sampled
//                       every slab, as before issue 23)
//   jitter              scene | on | off: per-pixel sample offset within each
//                       slab (scene: the scene's render.jitter)
// Passes
//   prepare: the shared resources and the meshes in world space with their
//            detail functions and material TFs (mesh_resources.h), when the
//            meshes change
//   render:  the layered depth image of the meshes (layered_depth_image.h)
//            when the camera, image size or meshes changed, then the slab
//            loop of slab_renderer.h (slabs and light buffers depend on the
//            camera and lights: every frame)
// rebuilds() counts the mesh and layered-depth-image rebuilds.
// Meshes: the scene's closed triangle meshes (scene/mesh.h) filled with
// volumetric detail; pathtrace draws them too (its reference), the others not.
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo convolution_info();

}  // namespace penumbra
