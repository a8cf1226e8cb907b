#include "server/render_queue.h"

#include "server/http_error.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <vector>

namespace penumbra::server {
namespace {

using namespace std::chrono_literals;

TEST(RenderQueue, RunsJobsAndPassesTheirErrorsOn) {
  RenderQueue queue(2, 8);
  int value = 0;
  queue.submit("a", false, [&] { value = 42; }).get();
  EXPECT_EQ(value, 42);
  auto failing = queue.submit("a", false, [] { throw HttpError(418, "k", "teapot"); });
  EXPECT_THROW(failing.get(), HttpError);
}

TEST(RenderQueue, JobsOfOneSessionNeverOverlapAndKeepTheirOrder) {
  RenderQueue queue(4, 64, 64);
  std::atomic<int> inside{0};
  std::atomic<int> max_inside{0};
  std::vector<int> order;
  std::vector<std::future<void>> jobs;
  for (int i = 0; i < 20; ++i) {
    jobs.push_back(queue.submit("same", false, [&, i] {
      max_inside = std::max(max_inside.load(), ++inside);
      order.push_back(i);  // safe only because jobs of a session are serial
      std::this_thread::sleep_for(1ms);
      --inside;
    }));
  }
  for (auto& j : jobs) j.get();
  EXPECT_EQ(max_inside.load(), 1);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(order[std::size_t(i)], i);
}

TEST(RenderQueue, JobsOfDifferentSessionsRunAtOnce) {
  RenderQueue queue(2, 8);
  // Both jobs hold their worker until released: both start only if jobs of
  // two sessions run at the same time.
  std::atomic<int> started{0};
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  auto a = queue.submit("a", false, [&] { ++started; released.wait(); });
  auto b = queue.submit("b", false, [&] { ++started; released.wait(); });
  for (int i = 0; i < 5000 && started.load() < 2; ++i) std::this_thread::sleep_for(1ms);
  EXPECT_EQ(started.load(), 2);
  EXPECT_EQ(queue.running(), 2);
  release.set_value();
  a.get();
  b.get();
}

TEST(RenderQueue, ANewerReplaceableJobSupersedesTheWaitingOne) {
  RenderQueue queue(1, 8);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> first_started{false};
  auto first = queue.submit("s", true, [&] { first_started = true; released.wait(); });
  while (!first_started) std::this_thread::yield();
  int ran = 0;
  auto second = queue.submit("s", true, [&] { ran = 2; });
  auto kept = queue.submit("s", false, [] {});         // not replaceable: stays
  auto third = queue.submit("s", true, [&] { ran = 3; });
  EXPECT_THROW(second.get(), Superseded);  // failed at once, without waiting for the worker
  release.set_value();
  first.get();
  kept.get();
  third.get();
  EXPECT_EQ(ran, 3);
}

TEST(RenderQueue, RefusesJobsBeyondTheWaitingLimit) {
  RenderQueue queue(1, 2);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  auto running = queue.submit("a", false, [&] { started = true; released.wait(); });
  while (!started) std::this_thread::yield();
  auto b = queue.submit("b", false, [] {});
  auto c = queue.submit("c", false, [] {});
  try {
    queue.submit("d", false, [] {});
    ADD_FAILURE() << "a third waiting job was accepted";
  } catch (const HttpError& e) {
    EXPECT_EQ(e.status(), 503);
  }
  release.set_value();
  running.get();
  b.get();
  c.get();
}

TEST(RenderQueue, OneSessionCannotFillTheWholeQueue) {
  RenderQueue queue(1, 16, 4);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  auto running = queue.submit("other", false, [&] { started = true; released.wait(); });
  while (!started) std::this_thread::yield();
  std::vector<std::future<void>> flood;
  for (int i = 0; i < 4; ++i) flood.push_back(queue.submit("flood", false, [] {}));
  try {
    queue.submit("flood", false, [] {});
    ADD_FAILURE() << "a fifth waiting job of one session was accepted";
  } catch (const HttpError& e) {
    EXPECT_EQ(e.status(), 503);
  }
  auto other = queue.submit("other", false, [] {});  // room for everybody else
  release.set_value();
  running.get();
  for (auto& f : flood) f.get();
  other.get();
}

TEST(RenderQueue, ShutdownFailsWaitingJobsAndFinishesRunningOnes) {
  std::future<void> running;
  std::future<void> waiting;
  std::atomic<bool> finished{false};
  // Declared before the queue: its destructor waits for the running job,
  // which reads them (ASan found them destroyed first, a use after scope).
  std::atomic<bool> started{false};
  std::atomic<bool> submitted{false};
  {
    RenderQueue queue(1, 8);
    // The running job lasts until the destructor has dropped the waiting one
    // (the only worker is busy here, so nothing else takes it off the queue).
    running = queue.submit("a", false, [&] {
      started = true;
      while (!submitted || queue.waiting() > 0) std::this_thread::sleep_for(1ms);
      finished = true;
    });
    while (!started) std::this_thread::yield();
    waiting = queue.submit("b", false, [] {});
    submitted = true;
  }
  running.get();
  EXPECT_TRUE(finished);
  EXPECT_THROW(waiting.get(), HttpError);
}

}  // namespace
}  // namespace penumbra::server
