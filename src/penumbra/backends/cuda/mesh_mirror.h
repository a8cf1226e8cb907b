#pragma once
// The scene's meshes as media (render/mesh_media.h) on the device: each
// material's detail (its noise table or texture volume), TF tables and BVH
// mirrored (DeviceMirror::mesh_array: uploaded again when the meshes, the TF
// or the data change, what MeshMedia rebuilds them on), the views copied for
// the frame.
// Host code only, like DeviceMirror; used by pathtrace's CUDA unit.
#include "penumbra/backends/cuda/device_mirror.h"
#include "penumbra/render/mesh_media.h"

#include <vector>

namespace penumbra {

namespace mesh_mirror_detail {

inline DetailView detail(DeviceMirror& m, DetailView d) {
  if (d.noise) d.noise = m.mesh_array(d.noise, 1, "a mesh's noise table");
  if (d.texture.data) d.texture = m.volume(d.texture, DeviceMirror::Grid::MeshDetail, "a mesh's detail texture");
  return d;
}

inline TransferFunctionView table(DeviceMirror& m, TransferFunctionView tf) {
  if (tf.size > 0) {
    tf.entries = m.mesh_array(tf.entries, std::size_t(tf.size), "a mesh's transfer function table");
    tf.sigma = m.mesh_array(tf.sigma, std::size_t(tf.size), "a mesh's transfer function table");
  }
  return tf;
}

}  // namespace mesh_mirror_detail

// `host` with every array it reaches replaced by its device copy.
inline MeshesView mirror_meshes(DeviceMirror& m, const MeshesView& host) {
  if (host.count == 0) return host;
  std::vector<MeshMaterialView> objects(host.objects, host.objects + host.count);
  for (MeshMaterialView& o : objects) {
    o.detail = mesh_mirror_detail::detail(m, o.detail);
    o.color_detail = mesh_mirror_detail::detail(m, o.color_detail);
    o.tf = mesh_mirror_detail::table(m, o.tf);
    o.color_tf = mesh_mirror_detail::table(m, o.color_tf);
  }
  MeshesView d = host;
  d.objects = m.frame(objects, "the meshes' materials");
  if (host.shapes) {
    std::vector<MeshBvhView> shapes(host.shapes, host.shapes + host.count);
    for (MeshBvhView& s : shapes) {
      s.nodes = m.mesh_array(s.nodes, std::size_t(s.node_count), "a mesh's BVH");
      s.triangles = m.mesh_array(s.triangles, std::size_t(s.triangle_count), "a mesh's BVH");
    }
    d.shapes = m.frame(shapes, "the meshes' BVHs");
  }
  return d;
}

}  // namespace penumbra
