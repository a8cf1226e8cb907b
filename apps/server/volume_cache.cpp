#include "server/volume_cache.h"

namespace penumbra::server {

LoadedVolume VolumeCache::get(const std::string& key, const std::function<LoadedVolume()>& load) {
  {
    std::lock_guard lock(mutex_);
    if (const auto it = entries_.find(key); it != entries_.end()) {
      if (auto volume = it->second.volume.lock()) return {std::move(volume), it->second.source};
      entries_.erase(it);
    }
  }
  LoadedVolume loaded = load();
  std::lock_guard lock(mutex_);
  ++loads_;
  for (auto it = entries_.begin(); it != entries_.end();) {
    it = it->second.volume.expired() ? entries_.erase(it) : std::next(it);
  }
  entries_[key] = Entry{loaded.volume, loaded.source};
  if (keep_recent_ > 0) {
    recent_.push_back(loaded.volume);
    while (recent_.size() > keep_recent_) recent_.pop_front();
  }
  return loaded;
}

std::size_t VolumeCache::loads() const {
  std::lock_guard lock(mutex_);
  return loads_;
}

}  // namespace penumbra::server
