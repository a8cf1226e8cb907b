#pragma once
// The sessions of all connected viewers, by id. Ids are random (128 bits) so
// one client cannot guess another's. The store holds at most `max_sessions`:
// creating one more evicts the least recently used, unless even that one was
// used within `eviction_grace` (then create() throws HttpError 503: every
// session is in use); sessions idle for longer than `idle_timeout` are
// evicted too. A render in progress keeps its session
// alive (jobs hold a shared_ptr) even if it is evicted meanwhile.
#include "server/session.h"

#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace penumbra::server {

class SessionStore {
 public:
  SessionStore(std::size_t max_sessions, std::chrono::seconds idle_timeout,
               std::chrono::seconds eviction_grace = std::chrono::seconds(0))
      : max_sessions_(max_sessions), idle_timeout_(idle_timeout), eviction_grace_(eviction_grace) {}

  std::shared_ptr<Session> create(SessionContext context);
  // Throws HttpError 404 for an unknown (or evicted) id.
  std::shared_ptr<Session> find(const std::string& id);
  bool remove(const std::string& id);
  std::size_t size() const;

 private:
  void evict_locked();

  const std::size_t max_sessions_;
  const std::chrono::seconds idle_timeout_;
  const std::chrono::seconds eviction_grace_;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Session>> sessions_;
};

}  // namespace penumbra::server
