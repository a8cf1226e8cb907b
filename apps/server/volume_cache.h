#pragma once
// Volumes loaded by the server, shared by every session that shows them, so
// that ten tabs on the same CT hold it once and a scene update that keeps the
// volume never reloads it. Entries are weak: a volume no session uses is
// freed, except the most recently loaded few, kept so that switching back and
// forth between volumes does not reread files.
#include "penumbra/scene/scene.h"

#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace penumbra::server {

struct LoadedVolume {
  std::shared_ptr<const Volume> volume;
  VolumeSource source;
};

class VolumeCache {
 public:
  explicit VolumeCache(std::size_t keep_recent = 2) : keep_recent_(keep_recent) {}

  // The volume cached under `key`, or load()'s result, cached. The load runs
  // outside the lock (other keys stay available while a big file is read).
  LoadedVolume get(const std::string& key, const std::function<LoadedVolume()>& load);

  // Loads that get() has performed (tests check reuse with it).
  std::size_t loads() const;

 private:
  struct Entry {
    std::weak_ptr<const Volume> volume;
    VolumeSource source;
  };
  mutable std::mutex mutex_;
  std::map<std::string, Entry> entries_;
  std::deque<std::shared_ptr<const Volume>> recent_;
  std::size_t keep_recent_;
  std::size_t loads_ = 0;
};

}  // namespace penumbra::server
