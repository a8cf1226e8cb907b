#pragma once
// The render workers. HTTP handler threads only parse requests and answer;
// anything slow (loading a volume, rebuilding light-space structures,
// rendering) runs here, so a slow render for one client never holds up
// another client's cheap requests.
//
// - Jobs of one session run one at a time, in order (they share its scene and
//   technique structures); jobs of different sessions run on different
//   workers at once.
// - A "replaceable" job (a frame that carries the whole scene) supersedes the
//   session's replaceable job that is still waiting: the waiting one fails
//   with Superseded (HTTP 409), because the newer frame shows everything it
//   would have. This is what keeps an interacting client from queueing up
//   stale preview frames.
// - At most `max_waiting` jobs wait in all, and at most
//   `max_waiting_per_session` of one session; beyond that submit() throws
//   HttpError 503, so a flood of requests cannot pile up handler threads,
//   and one client's flood cannot turn every other client's frames away.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace penumbra::server {

class Superseded : public std::runtime_error {
 public:
  Superseded() : std::runtime_error("superseded by a newer frame of the same session") {}
};

class RenderQueue {
 public:
  RenderQueue(int workers, int max_waiting, int max_waiting_per_session = 4);
  ~RenderQueue();  // waiting jobs fail (HttpError 503), running ones finish
  RenderQueue(const RenderQueue&) = delete;
  RenderQueue& operator=(const RenderQueue&) = delete;

  // Queues `job` for `session`. The future rethrows whatever the job threw.
  std::future<void> submit(const std::string& session, bool replaceable, std::function<void()> job);

  int waiting() const;
  int running() const;

  // Tests: called on the worker right before each job starts (to hold jobs
  // back deterministically, without timing).
  void set_start_hook(std::function<void()> hook);

 private:
  struct Job {
    std::string session;
    bool replaceable = false;
    std::function<void()> work;
    std::promise<void> done;
  };
  void worker_loop();

  const int max_waiting_;
  const int max_waiting_per_session_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> waiting_;
  std::multiset<std::string> running_sessions_;
  std::function<void()> start_hook_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace penumbra::server
