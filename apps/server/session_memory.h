#pragma once
// What the sessions' own structures hold (the techniques' light-space
// structures and caches, the last image), against one budget for all of
// them: each allocation is checked against the process's memory budget as it
// is made, and this bounds their sum, so sixteen sessions that each build a
// large structure cannot hold sixteen budgets between them.
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace penumbra::server {

class SessionMemory {
 public:
  // 0: the process's memory budget (memory_budget.h) at the time of the check.
  explicit SessionMemory(std::uint64_t budget = 0) : budget_(budget) {}

  // Records what session `id` holds now; throws OutOfMemoryBudget when the
  // sum over all sessions exceeds the budget (the record stays, so the caller
  // can release and record again).
  void record(const std::string& id, std::uint64_t bytes);
  void forget(const std::string& id);

  std::uint64_t total() const;
  std::uint64_t budget() const;

 private:
  const std::uint64_t budget_;
  mutable std::mutex mutex_;
  std::map<std::string, std::uint64_t> bytes_;
};

}  // namespace penumbra::server
