#include "server/session_store.h"

#include "server/http_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <random>

namespace penumbra::server {
namespace {

std::string random_id() {
  static std::mutex mutex;
  static std::random_device device;
  std::lock_guard lock(mutex);
  std::uniform_int_distribution<std::uint32_t> word;
  return fmt::format("{:08x}{:08x}{:08x}{:08x}", word(device), word(device), word(device), word(device));
}

}  // namespace

std::shared_ptr<Session> SessionStore::create(SessionContext context) {
  auto session = std::make_shared<Session>(random_id(), context);
  std::lock_guard lock(mutex_);
  evict_locked();
  while (sessions_.size() >= std::max<std::size_t>(1, max_sessions_)) {
    const auto oldest = std::min_element(sessions_.begin(), sessions_.end(), [](const auto& a, const auto& b) {
      return a.second->last_used() < b.second->last_used();
    });
    if (std::chrono::steady_clock::now() - oldest->second->last_used() < eviction_grace_) {
      throw HttpError(503, "session",
                      fmt::format("the server holds its {} sessions and every one was used in the last {} s; try "
                                  "again later (or DELETE a session you no longer need)",
                                  sessions_.size(), eviction_grace_.count()));
    }
    sessions_.erase(oldest);
  }
  sessions_[session->id()] = session;
  return session;
}

std::shared_ptr<Session> SessionStore::find(const std::string& id) {
  std::lock_guard lock(mutex_);
  evict_locked();
  const auto it = sessions_.find(id);
  if (it == sessions_.end()) {
    throw HttpError(404, "session", "unknown session (it may have expired): create one with POST /api/sessions");
  }
  it->second->touch();
  return it->second;
}

bool SessionStore::remove(const std::string& id) {
  std::lock_guard lock(mutex_);
  return sessions_.erase(id) > 0;
}

std::size_t SessionStore::size() const {
  std::lock_guard lock(mutex_);
  return sessions_.size();
}

void SessionStore::evict_locked() {
  const auto now = std::chrono::steady_clock::now();
  std::erase_if(sessions_, [&](const auto& item) { return now - item.second->last_used() > idle_timeout_; });
}

}  // namespace penumbra::server
