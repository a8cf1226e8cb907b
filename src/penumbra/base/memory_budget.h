#pragma once
// Every large allocation (voxels, light-space structures, images) is checked
// against one process-wide budget before it is made, so a header that claims
// 100 GB gives OutOfMemoryBudget instead of a crash. Default: half of physical
// memory; PENUMBRA_MEMORY_BUDGET_MB overrides it.
#include <cstdint>
#include <initializer_list>
#include <string>

namespace penumbra {

std::uint64_t memory_budget_bytes();
void set_memory_budget_bytes(std::uint64_t bytes);

// Throws OutOfMemoryBudget naming `what` when `bytes` exceeds the budget.
void check_memory_budget(const std::string& what, std::uint64_t bytes);

// Product of the factors, or nullopt-like UINT64_MAX on overflow (which then
// fails the budget check with a clear message).
std::uint64_t checked_product(std::initializer_list<std::uint64_t> factors);

}  // namespace penumbra
