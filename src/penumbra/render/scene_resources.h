#pragma once
// SceneResources: the structures every technique shares, kept up to date with
// the scene's version counters: the macrocell min/max grid and, when Phong
// shading needs them, precomputed shading normals (rebuilt when the data
// changes), the baked transfer function table and the per-macrocell majorant
// extinction (rebuilt when the data or the TF changes).
#include "penumbra/render/majorant_grid.h"
#include "penumbra/render/render_view.h"
#include "penumbra/scene/scene.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra {

class SceneResources {
 public:
  // Brings the shared structures up to date; returns true when the data or
  // the TF changed since the last call (so techniques know to rebuild too).
  // Shading normals are built (once per data change) when `normals` is true:
  // techniques that shade with Phong pass it.
  bool update(const Scene& scene, bool normals = false);

  // A view for rendering the scene at its render size (update() first).
  RenderView view(const Scene& scene) const;
  // The same view with the shadow TF's table and majorants, for shadow rays
  // and light-space structures (identical to view() without a shadow TF).
  RenderView shadow_view(const Scene& scene) const;
  const TransferFunctionTable& tf_table() const { return tf_table_; }
  const MacrocellGrid& macrocells() const { return macrocells_; }
  const MajorantGrid& majorants() const { return majorants_; }

  // Memory of the shared structures (not counted as a technique's aux_bytes).
  std::uint64_t bytes() const;

 private:
  std::uint64_t data_version_ = 0;
  std::uint64_t tf_version_ = 0;
  MacrocellGrid macrocells_;
  NormalVolume normals_;
  TransferFunctionTable tf_table_;
  MajorantGrid majorants_;
  bool separate_shadow_tf_ = false;
  TransferFunctionTable shadow_tf_table_;
  MajorantGrid shadow_majorants_;
  // A device backend's mirrors of the views' arrays (RenderView::device_state).
  mutable std::shared_ptr<void> device_state_;
};

}  // namespace penumbra
