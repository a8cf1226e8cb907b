#pragma once
// Things loaded from files (volumes, meshes, texture volumes) shared by every
// session that shows them, by key. One load per key however many sessions
// ask at once: the first caller loads outside the lock, later callers for the
// same key wait for that load and share its result (or its error), so ten
// tabs opening the same CT read it once and hold it once. Entries are weak: a
// value no session uses is freed, except the `keep_recent` most recently
// loaded, kept so that switching back and forth does not reread files.
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace penumbra::server {

template <class T> class LoadCache {
 public:
  using Loader = std::function<std::shared_ptr<const T>()>;

  explicit LoadCache(std::size_t keep_recent) : keep_recent_(keep_recent) {}

  std::shared_ptr<const T> get(const std::string& key, const Loader& load) {
    std::promise<std::shared_ptr<const T>> promise;
    {
      std::unique_lock lock(mutex_);
      if (const auto it = entries_.find(key); it != entries_.end()) {
        if (auto value = it->second.lock()) return value;
        entries_.erase(it);
      }
      if (const auto it = loading_.find(key); it != loading_.end()) {
        std::shared_future<std::shared_ptr<const T>> pending = it->second;
        lock.unlock();
        return pending.get();  // rethrows the loader's error
      }
      loading_.emplace(key, promise.get_future().share());
    }
    std::shared_ptr<const T> value;
    try {
      value = load();
    } catch (...) {
      std::lock_guard lock(mutex_);
      promise.set_exception(std::current_exception());
      loading_.erase(key);  // a later request tries again (the file may have been fixed)
      throw;
    }
    std::lock_guard lock(mutex_);
    ++loads_;
    for (auto it = entries_.begin(); it != entries_.end();) it = it->second.expired() ? entries_.erase(it) : std::next(it);
    entries_[key] = value;
    if (keep_recent_ > 0) {
      recent_.push_back(value);
      while (recent_.size() > keep_recent_) recent_.pop_front();
    }
    promise.set_value(value);
    loading_.erase(key);
    return value;
  }

  // Loads performed (tests check sharing with it).
  std::size_t loads() const {
    std::lock_guard lock(mutex_);
    return loads_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::weak_ptr<const T>> entries_;
  std::map<std::string, std::shared_future<std::shared_ptr<const T>>> loading_;
  std::deque<std::shared_ptr<const T>> recent_;
  const std::size_t keep_recent_;
  std::size_t loads_ = 0;
};

}  // namespace penumbra::server
