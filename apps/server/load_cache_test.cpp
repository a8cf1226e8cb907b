#include "server/load_cache.h"

#include "server/session_memory.h"

#include "penumbra/base/error.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>

namespace penumbra::server {
namespace {

using namespace std::chrono_literals;

TEST(LoadCache, ConcurrentRequestsForOneKeyShareOneLoad) {
  LoadCache<int> cache(0);
  std::atomic<int> calls{0};
  std::promise<void> started, gate;
  auto gate_future = gate.get_future().share();
  auto slow_load = [&] {
    ++calls;
    started.set_value();
    gate_future.wait();
    return std::make_shared<const int>(42);
  };
  auto first = std::async(std::launch::async, [&] { return cache.get("ct.nhdr", slow_load); });
  started.get_future().wait();
  // A second session asks while the first load runs: it must wait for it.
  auto second = std::async(std::launch::async, [&] { return cache.get("ct.nhdr", slow_load); });
  std::this_thread::sleep_for(50ms);
  gate.set_value();
  const auto a = first.get();
  const auto b = second.get();
  EXPECT_EQ(a, b);
  EXPECT_EQ(*a, 42);
  EXPECT_EQ(calls.load(), 1);
  EXPECT_EQ(cache.loads(), 1u);
}

TEST(LoadCache, AFailedLoadReachesEveryWaiterAndIsTriedAgainLater) {
  LoadCache<int> cache(2);
  EXPECT_THROW(cache.get("bad", []() -> std::shared_ptr<const int> { throw IoError("bad", "truncated"); }), IoError);
  const auto fixed = cache.get("bad", [] { return std::make_shared<const int>(7); });
  EXPECT_EQ(*fixed, 7);
  EXPECT_EQ(cache.loads(), 1u);
}

TEST(LoadCache, UnusedValuesAreFreedBeyondTheRecentOnes) {
  LoadCache<int> cache(1);
  std::weak_ptr<const int> first = cache.get("a", [] { return std::make_shared<const int>(1); });
  (void)cache.get("b", [] { return std::make_shared<const int>(2); });  // "a" is no longer among the recent
  EXPECT_TRUE(first.expired());
  std::weak_ptr<const int> second = cache.get("b", [] { return std::make_shared<const int>(3); });
  EXPECT_FALSE(second.expired());  // kept as the most recent, and not loaded again
  EXPECT_EQ(cache.loads(), 2u);
}

TEST(SessionMemory, TheSumOverSessionsIsBoundedByTheBudget) {
  SessionMemory memory(100);
  memory.record("a", 60);
  memory.record("b", 30);
  EXPECT_THROW(memory.record("b", 50), OutOfMemoryBudget);
  EXPECT_EQ(memory.total(), 110u);  // the record stays until the session releases
  memory.forget("a");
  EXPECT_NO_THROW(memory.record("b", 50));
  EXPECT_EQ(memory.total(), 50u);
}

}  // namespace
}  // namespace penumbra::server
