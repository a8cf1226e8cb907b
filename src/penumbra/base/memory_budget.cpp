#include "penumbra/base/memory_budget.h"

#include "penumbra/base/error.h"

#include <atomic>
#include <cstdlib>
#include <limits>

#include <unistd.h>

namespace penumbra {
namespace {

std::uint64_t default_budget() {
  if (const char* env = std::getenv("PENUMBRA_MEMORY_BUDGET_MB")) {
    char* end = nullptr;
    const unsigned long long mb = std::strtoull(env, &end, 10);
    if (end != env && *end == '\0' && mb > 0) return mb * 1024ull * 1024ull;
  }
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 4ull << 30;  // unknown: a safe 4 GiB
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size) / 2;
}

std::atomic<std::uint64_t>& budget() {
  static std::atomic<std::uint64_t> value{default_budget()};
  return value;
}

}  // namespace

std::uint64_t memory_budget_bytes() { return budget().load(); }

void set_memory_budget_bytes(std::uint64_t bytes) { budget().store(bytes); }

void check_memory_budget(const std::string& what, std::uint64_t bytes) {
  const std::uint64_t limit = memory_budget_bytes();
  if (bytes > limit) throw OutOfMemoryBudget(what, bytes, limit);
}

std::uint64_t checked_product(std::initializer_list<std::uint64_t> factors) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t result = 1;
  for (std::uint64_t f : factors) {
    if (f != 0 && result > kMax / f) return kMax;
    result *= f;
  }
  return result;
}

}  // namespace penumbra
