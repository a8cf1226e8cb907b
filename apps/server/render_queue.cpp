#include "server/render_queue.h"

#include "server/http_error.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::server {

RenderQueue::RenderQueue(int workers, int max_waiting, int max_waiting_per_session)
    : max_waiting_(std::max(1, max_waiting)), max_waiting_per_session_(std::max(1, max_waiting_per_session)) {
  for (int i = 0; i < std::max(1, workers); ++i) workers_.emplace_back([this] { worker_loop(); });
}

RenderQueue::~RenderQueue() {
  std::deque<Job> dropped;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    dropped.swap(waiting_);
  }
  wake_.notify_all();
  for (Job& job : dropped) {
    job.done.set_exception(std::make_exception_ptr(HttpError(503, "", "the server is shutting down")));
  }
  for (std::thread& t : workers_) t.join();
}

std::future<void> RenderQueue::submit(const std::string& session, bool replaceable, std::function<void()> job) {
  Job entry{session, replaceable, std::move(job), {}};
  std::future<void> future = entry.done.get_future();
  {
    std::lock_guard lock(mutex_);
    if (stopping_) throw HttpError(503, "", "the server is shutting down");
    if (replaceable) {
      const auto old = std::find_if(waiting_.begin(), waiting_.end(),
                                    [&](const Job& j) { return j.replaceable && j.session == session; });
      if (old != waiting_.end()) {
        old->done.set_exception(std::make_exception_ptr(Superseded()));
        waiting_.erase(old);
      }
    }
    // One session (one client flooding frames) may not fill the whole queue
    // and so turn every other session's frames away.
    const auto own = std::count_if(waiting_.begin(), waiting_.end(), [&](const Job& j) { return j.session == session; });
    if (own >= max_waiting_per_session_) {
      throw HttpError(503, "", fmt::format("busy: this session already has {} renders waiting; try again shortly", own));
    }
    if (int(waiting_.size()) >= max_waiting_) {
      throw HttpError(503, "", fmt::format("busy: {} renders are waiting; try again shortly", waiting_.size()));
    }
    waiting_.push_back(std::move(entry));
  }
  wake_.notify_one();
  return future;
}

int RenderQueue::waiting() const {
  std::lock_guard lock(mutex_);
  return int(waiting_.size());
}

int RenderQueue::running() const {
  std::lock_guard lock(mutex_);
  return int(running_sessions_.size());
}

void RenderQueue::set_start_hook(std::function<void()> hook) {
  std::lock_guard lock(mutex_);
  start_hook_ = std::move(hook);
}

void RenderQueue::worker_loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    // The oldest job whose session is not already running.
    auto next = waiting_.end();
    wake_.wait(lock, [&] {
      if (stopping_) return true;
      next = std::find_if(waiting_.begin(), waiting_.end(),
                          [&](const Job& j) { return running_sessions_.count(j.session) == 0; });
      return next != waiting_.end();
    });
    if (stopping_) return;
    Job job = std::move(*next);
    waiting_.erase(next);
    running_sessions_.insert(job.session);
    const std::function<void()> hook = start_hook_;
    lock.unlock();
    try {
      if (hook) hook();
      job.work();
      job.done.set_value();
    } catch (...) {
      job.done.set_exception(std::current_exception());
    }
    lock.lock();
    running_sessions_.erase(running_sessions_.find(job.session));
    // A job of this session may be waiting for it to finish.
    wake_.notify_all();
  }
}

}  // namespace penumbra::server
