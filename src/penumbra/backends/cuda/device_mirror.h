#pragma once
// DeviceMirror: what a Lighting's on_device() (backends/device.h) maps its
// host pointers with, for one frame. Arrays that only change with the scene
// are uploaded once per version of what they depend on (DeviceCache::
// persistent); small structs and arrays of views are copied every frame.
//
// Versions: the volume and its shading normals follow the data; the
// macrocell grid, majorants and TF tables the data and the TF; a
// technique's own structures everything but the camera, and the technique's
// rebuilds() count (RenderView::structures); the meshes' arrays the meshes,
// the data and the TF.
//
// Host code only; used by the .cu units of the techniques.
#include "penumbra/backends/cuda/device_cache.h"
#include "penumbra/base/rng.h"
#include "penumbra/render/render_view.h"
#include "penumbra/volume/voxel_type.h"

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace penumbra {

class DeviceMirror {
 public:
  DeviceMirror(DeviceCache& cache, const RenderView& host) : cache_(cache), host_(host) {
    const SceneVersions& s = host.versions;
    data_version_ = mix_bits(s.data);
    tf_version_ = mix_bits(data_version_ ^ mix_bits(s.transfer_function + 1));
    std::uint64_t all = tf_version_;
    for (std::uint64_t part : {s.lights, s.material, s.geometry, s.render, s.meshes, host.structures}) {
      all = mix_bits(all ^ (part + 0x9e3779b97f4a7c15ull));
    }
    structures_version_ = all;
    // MeshMedia (render/mesh_media.h) rebuilds its arrays when the meshes
    // change or the TF's unit length does, which follows the TF and the
    // volume's spacing.
    meshes_version_ = mix_bits(tf_version_ ^ mix_bits(s.meshes + 0x51ed27));
  }

  int light_count() const { return host_.light_count; }

  // A technique structure: uploaded when its version changed.
  template <class T> const T* structure(const T* host, std::size_t count, const char* what = "technique structures") {
    return static_cast<const T*>(cache_.persistent(host, count * sizeof(T), structures_version_, what));
  }
  // An array of the scene's meshes as media (mesh_mirror.h): uploaded when
  // the meshes, the TF or the data changed, not on a light, camera or
  // material edit.
  template <class T> const T* mesh_array(const T* host, std::size_t count, const char* what) {
    return static_cast<const T*>(cache_.persistent(host, count * sizeof(T), meshes_version_, what));
  }
  // Copied to the device for this frame only (views, small arrays).
  template <class T> const T* frame(const T* host, std::size_t count, const char* what = "per-frame data") {
    return static_cast<const T*>(cache_.frame(host, count * sizeof(T), what));
  }
  template <class T> const T* frame(const std::vector<T>& host, const char* what = "per-frame data") {
    return frame(host.data(), host.size(), what);
  }

  // A grid of voxels (the volume, a shadow cache, a mesh's detail texture):
  // its data mirrored.
  enum class Grid : std::uint8_t { SceneData, Structure, MeshDetail };
  VolumeView volume(VolumeView grid, bool scene_data, const char* what) {
    return volume(grid, scene_data ? Grid::SceneData : Grid::Structure, what);
  }
  VolumeView volume(VolumeView grid, Grid kind, const char* what) {
    const std::size_t bytes = std::size_t(grid.dims.x) * grid.dims.y * grid.dims.z * voxel_size(grid.type);
    const std::uint64_t version = kind == Grid::SceneData    ? data_version_
                                  : kind == Grid::MeshDetail ? meshes_version_
                                                             : structures_version_;
    grid.data = cache_.persistent(grid.data, bytes, version, what);
    return grid;
  }
  // Per-light grids (the shadow caches), as a device array of views.
  const VolumeView* volumes(const VolumeView* host, int count, const char* what) {
    std::vector<VolumeView> copy(host, host + count);
    for (VolumeView& grid : copy) grid = volume(grid, false, what);
    return frame(copy, what);
  }

  // A render view: its arrays mirrored, the view itself copied for this
  // frame (once per host view, so a Lighting's view pointer and the kernel's
  // view are the same copy). `cells` says how its majorants and empty-space
  // distances are versioned: with the data and TF (the scene's), or copied
  // every frame (a technique's own occupancy, which follows one of its
  // parameters: occlusion-map's iso-value; a few bytes per macrocell).
  enum class Cells : std::uint8_t { FollowTf, PerFrame };
  const RenderView* view(const RenderView& host, Cells cells_version = Cells::FollowTf) {
    const auto found = views_.find(&host);
    if (found != views_.end()) return found->second;
    RenderView d = host;
    d.volume = volume(host.volume, true, "the volume");
    const std::size_t cells = std::size_t(host.macrocells.dims.x) * host.macrocells.dims.y * host.macrocells.dims.z;
    d.macrocells.min_max = tf_array(host.macrocells.min_max, cells, "the macrocell grid");
    if (cells_version == Cells::PerFrame) {
      d.majorants = frame(host.majorants, cells, "the occupancy grid");
      d.empty_distance = frame(host.empty_distance, cells, "the empty-space distances");
    } else {
      d.majorants = tf_array(host.majorants, cells, "the majorant grid");
      d.empty_distance = tf_array(host.empty_distance, cells, "the empty-space distances");
    }
    d.tf.entries = tf_array(host.tf.entries, std::size_t(host.tf.size), "the transfer function table");
    d.tf.sigma = tf_array(host.tf.sigma, std::size_t(host.tf.size), "the transfer function table");
    if (host.normals.texels) {
      d.normals.texels = static_cast<const std::int8_t*>(cache_.persistent(
          host.normals.texels, std::size_t(host.normals.grid.count) * 4, data_version_, "the shading normals"));
    }
    d.clip_planes = frame(host.clip_planes, std::size_t(host.clip_plane_count));
    d.planes = frame(host.planes, std::size_t(host.plane_count));
    d.lights = frame(host.lights, std::size_t(host.light_count));
    d.device_state = nullptr;
    const RenderView* device = frame(&d, 1, "the render view");
    views_.emplace(&host, device);
    return device;
  }

 private:
  template <class T> const T* tf_array(const T* host, std::size_t count, const char* what) {
    return static_cast<const T*>(cache_.persistent(host, count * sizeof(T), tf_version_, what));
  }

  DeviceCache& cache_;
  const RenderView& host_;
  std::uint64_t data_version_ = 0;
  std::uint64_t tf_version_ = 0;
  std::uint64_t structures_version_ = 0;
  std::uint64_t meshes_version_ = 0;
  std::unordered_map<const RenderView*, const RenderView*> views_;
};

}  // namespace penumbra
