#pragma once
// What the server loads from its data folder, shared by every session
// (load_cache.h): volumes by their scene section (a scene update that keeps
// the volume never reloads it), and mesh files and mesh texture volumes by
// their real path (a scene PUT that keeps its meshes never rereads them).
#include "penumbra/scene/mesh.h"
#include "penumbra/volume/volume.h"
#include "server/load_cache.h"

#include <cstddef>
#include <memory>
#include <string>

namespace penumbra::server {

class VolumeCache {
 public:
  explicit VolumeCache(std::size_t keep_recent = 2) : volumes_(keep_recent), textures_(keep_recent), meshes_(8) {}

  // The volume of a scene's volume section (`key`), loaded once.
  std::shared_ptr<const Volume> volume(const std::string& key, const LoadCache<Volume>::Loader& load) {
    return volumes_.get(key, load);
  }
  // A mesh's texture volume or a mesh file, by its real path.
  std::shared_ptr<const Volume> texture(const std::string& path, const LoadCache<Volume>::Loader& load) {
    return textures_.get(path, load);
  }
  std::shared_ptr<const TriangleMesh> mesh(const std::string& path, const LoadCache<TriangleMesh>::Loader& load) {
    return meshes_.get(path, load);
  }

  // Loads performed (tests check reuse with them).
  std::size_t loads() const { return volumes_.loads(); }
  std::size_t texture_loads() const { return textures_.loads(); }
  std::size_t mesh_loads() const { return meshes_.loads(); }

 private:
  LoadCache<Volume> volumes_;
  LoadCache<Volume> textures_;
  LoadCache<TriangleMesh> meshes_;
};

}  // namespace penumbra::server
