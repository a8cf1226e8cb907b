#pragma once
// RenderView: everything a per-ray kernel reads, as one plain struct of views
// and values (no ownership). Host code (SceneResources) builds it once per
// frame; the CPU backend passes it by reference to every tile, a CUDA backend
// would copy it to the device.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/light.h"
#include "penumbra/scene/material.h"
#include "penumbra/scene/plane.h"
#include "penumbra/scene/scene_versions.h"
#include "penumbra/scene/transfer_function.h"
#include "penumbra/volume/macrocell_grid.h"
#include "penumbra/volume/normal_volume.h"
#include "penumbra/volume/volume_view.h"

#include <cstdint>
#include <memory>

namespace penumbra {

struct RenderView {
  VolumeView volume;
  MacrocellView macrocells;
  const float* majorants = nullptr;  // per macrocell: the largest sigma_t any sample there can have (0 = empty)
  const std::uint8_t* empty_distance = nullptr;  // per macrocell: chessboard distance to a non-empty one
  TransferFunctionView tf;
  NormalView normals;  // precomputed shading normals, or texels == nullptr for on-the-fly gradients
  Box3 box;            // the volume's world box

  const vec4* clip_planes = nullptr;
  int clip_plane_count = 0;
  const Plane* planes = nullptr;
  int plane_count = 0;
  const Light* lights = nullptr;
  int light_count = 0;

  Material material;
  vec3 background{0.0f};
  float step = 1.0f;            // world units
  float ert_threshold = 0.99f;  // stop when accumulated opacity reaches this
  bool jitter = false;

  CameraView camera;
  int width = 0;
  int height = 0;

  // Host side only (a device copy carries but never reads them): the scene's
  // versions when the view was made, the version of the technique's own
  // structures (its rebuilds() count), and the slot where a device backend
  // keeps the mirrors of this view's arrays (SceneResources owns it, so the
  // mirrors live as long as the technique). The CUDA backend re-uploads an
  // array only when a version it depends on changed.
  SceneVersions versions;
  std::uint64_t structures = 0;
  std::shared_ptr<void>* device_state = nullptr;

  // The majorant of the macrocell around an index-space point (clamped to
  // the grid): 0 where no sample can have extinction, so a kernel may skip
  // the volume lookup there.
  // Written over a lane type (base/lanes.h); the float form is its one-lane
  // instance. Lanes that are off must hold a finite index (the gather reads
  // every lane). The macrocell offset is MacrocellView::index's, in 32 bits.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float majorant_at(const typename L::Vec3& index) const {
    using F = typename L::Float;
    using I = typename L::Int;
    const float size = float(macrocells.cell_size);
    const I x = to_int_nonnegative(clamp(floor(index.x / size), F(0.0f), F(float(macrocells.dims.x - 1))));
    const I y = to_int_nonnegative(clamp(floor(index.y / size), F(0.0f), F(float(macrocells.dims.y - 1))));
    const I z = to_int_nonnegative(clamp(floor(index.z / size), F(0.0f), F(float(macrocells.dims.z - 1))));
    return gather(majorants, typename L::Index(x + I(macrocells.dims.x) * (y + I(macrocells.dims.y) * z)));
  }
  PENUMBRA_HD float majorant_at(vec3 index) const { return majorant_at<ScalarLanes>(index); }
};

}  // namespace penumbra
