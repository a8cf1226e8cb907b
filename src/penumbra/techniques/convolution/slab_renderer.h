#pragma once
// The slab loop of Patel et al. 2013, section 4.2, for plain volumes: slabs
// perpendicular to the camera's forward axis through the volume box (and on
// to the farthest plane hit, at most one box diagonal beyond it), front to
// back. Per slab: (1) every light's buffer is convolved from the previous
// slab's outgoing light (light_propagation.h), and a zero-variance light's
// pixels whose light crossed only empty space take it from the grid that
// carries it along its rays (carried_light.h); then per pixel (3) the volume
// is sampled once at the middle (or, with jitter, at the pixel's hashed
// offset) of the part of the slab that lies inside the box and clip planes (the TF-classified scalar field; that part's length
// along the ray is the segment length) and shaded by the shared
// ScatteringLighting with the buffers as visibility, attenuated by the half
// of the segment in front of the sample (the ray caster's midpoint rule),
// (4) composited front to back, and the outgoing light is the incoming light
// times the segment's transmittance toward each light
// exp(-sigma_t(shadow TF) e' / (d . f)), e' the slab thickness inside. An opaque plane crossing the slab is
// shaded with the incoming light; it does not zero the buffer behind it (the
// shared shading already blocks light by planes, and a zeroed texel under a
// plane tilted against the slabs would bleed into its neighbours above the
// plane through the kernel). A plane beyond the last slab is shaded with the
// last slab's light.
// Early ray termination stops the shading of a pixel, never its light
// update (neighbours read it through the kernel).
// Behind the box (of the volume and the meshes) the slabs down to a far
// floor hold no medium: once the carried grids have been clear for a while
// they only step the grids, convolve the soft lights' buffers and light the
// plane hits in them (the empty tail, slab_renderer.cpp).
// Meshes (step 2): each pixel walks its layered depth image fragments slab by
// slab (mesh_layers.h); the part of the slab inside a mesh is one more
// sample, of the mesh's detail function through its material TF, lit with
// the phase function like the volume (the paper's "purely diffuse"
// illumination) and composited with the volume's sample in depth order; the
// first surface a ray enters in a slab adds the microfacet highlight
// (render/microfacet.h). Both media attenuate the light buffers: grey, or
// per colour channel (three buffers per light) when a mesh's material has a
// transport colour (its light extinction sigma_t (1 - transport_color);
// Patel et al. 2013, Fig. 7e). With a mesh in the scene the light crosses
// the meshes' and the box's surfaces along slanted paths, not down each
// pixel's column (slanted_paths.h: the slab rings of issue 23); the buffers
// are attenuated after each slab's pixel loop.
// Preintegrated compositing (optional): the volume segment between the
// previous slab's sample and this one takes its opacity and colour from the
// preintegration table of the TF (preintegration.h) instead of one point.
#include "penumbra/render/image.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/scene/scene.h"
#include "penumbra/techniques/convolution/carried_light.h"
#include "penumbra/techniques/convolution/gaussian_light.h"
#include "penumbra/techniques/convolution/mesh_resources.h"
#include "penumbra/techniques/convolution/preintegration.h"
#include "penumbra/techniques/convolution/slanted_paths.h"
#include "penumbra/techniques/convolution/slab_kernel.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct SlabSettings {
  float slab_distance_voxels = 0.0f;     // 0: the render step and the meshes' detail (automatic_slab_distance)
  float optimal_distance_voxels = 0.0f;  // 0: a quarter of the box's depth extent
  SlabKernelType kernel = SlabKernelType::Ellipse;
  int kernel_samples = 0;  // 0: the kernel's default
  LightOverride light;
  std::uint64_t seed = 1;
  bool preintegrated = false;
  bool guard_band = true;  // light buffers over a band around the image (slab_renderer.cpp)
  bool jitter = false;     // per-pixel sample offset within each slab (render.jitter, or the technique's knob)
  bool carried_light = true;  // zero-variance lights also carried along their rays across empty space
  bool empty_tail = true;  // past every medium, slabs read the carried light only where a plane is hit (tests: false)
};

class SlabRenderer {
 public:
  void prepare(const Scene& scene, const SlabSettings& settings);
  void render(const Scene& scene, Image& image, RenderStats* stats = nullptr);
  std::uint64_t aux_bytes() const;
  int last_slab_count() const { return last_slabs_; }
  // Slabs of the last frame that only stepped the carried grids and lit the
  // plane hits in them (the empty tail, slab_renderer.cpp).
  int last_tail_slabs() const { return last_tail_slabs_; }
  int rebuilds() const { return meshes_.builds(); }
  static constexpr int kAutomaticSlabs = 4096;  // the most slabs an unset slab_distance gives
  // An unset slab_distance also keeps every light's sideways drift per slab
  // (e tan of its angle to the view) within a voxel, taking up to this many
  // times the slabs the step and the detail give.
  static constexpr float kMaxDriftRefinement = 4.0f;

 private:
  float automatic_slab_distance(const RenderView& view, const RenderView& shadow, float depth,
                                const std::vector<GaussianLight>& lights) const;
  // Whether the volume has any extinction, for the viewer or through a shadow TF.
  bool volume_has_extinction(const RenderView& view, const RenderView& shadow) const;
  SceneResources resources_;
  MeshResources meshes_;
  PreintegrationCache preintegration_;
  SlabSettings settings_;
  CarriedLights carried_;  // zero-variance lights' grids (carried_light.h)
  SlantedPaths slanted_;  // light paths across slabs where they meet a surface (slanted_paths.h)
  std::vector<float> buffers_;  // 2 per light, ping-pong: the light's transmittance, grey or per channel (DESIGN-NOTES)
  int last_slabs_ = 0;
  int last_tail_slabs_ = 0;
};

}  // namespace penumbra
