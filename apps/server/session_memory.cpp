#include "server/session_memory.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"

namespace penumbra::server {

void SessionMemory::record(const std::string& id, std::uint64_t bytes) {
  std::uint64_t sum = 0;
  {
    std::lock_guard lock(mutex_);
    bytes_[id] = bytes;
    for (const auto& [other, b] : bytes_) sum += b;
  }
  if (sum > budget()) throw OutOfMemoryBudget("the structures of the server's sessions", sum, budget());
}

void SessionMemory::forget(const std::string& id) {
  std::lock_guard lock(mutex_);
  bytes_.erase(id);
}

std::uint64_t SessionMemory::total() const {
  std::lock_guard lock(mutex_);
  std::uint64_t sum = 0;
  for (const auto& [id, b] : bytes_) sum += b;
  return sum;
}

std::uint64_t SessionMemory::budget() const { return budget_ > 0 ? budget_ : memory_budget_bytes(); }

}  // namespace penumbra::server
