#include "penumbra/base/error.h"

#include <fmt/format.h>

namespace penumbra {

IoError::IoError(std::string path, const std::string& what)
    : Error(fmt::format("{}: {}", path, what)), path_(std::move(path)) {}

InvalidScene::InvalidScene(std::string key, const std::string& what)
    : Error(fmt::format("scene key '{}': {}", key, what)), key_(std::move(key)) {}

InvalidArgument::InvalidArgument(std::string name, const std::string& what)
    : Error(fmt::format("'{}': {}", name, what)), name_(std::move(name)) {}

OutOfMemoryBudget::OutOfMemoryBudget(const std::string& what, std::uint64_t bytes, std::uint64_t budget)
    : Error(fmt::format("{} needs {:.1f} MiB, over the memory budget of {:.1f} MiB (by default half of physical "
                        "memory; PENUMBRA_MEMORY_BUDGET_MB sets it)",
                        what,
                        static_cast<double>(bytes) / (1024.0 * 1024.0),
                        static_cast<double>(budget) / (1024.0 * 1024.0))),
      bytes_(bytes) {}

}  // namespace penumbra
