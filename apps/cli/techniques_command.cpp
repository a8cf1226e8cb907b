// penumbra techniques: every technique with its parameters, defaults, ranges
// and one-line docs (the registry's parameter tables).
#include "commands.h"

#include "penumbra/techniques/registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace penumbra::cli {
namespace {

std::string describe_range(const ParameterSpec& spec) {
  switch (spec.type) {
    case ParameterType::Float:
    case ParameterType::Int: return fmt::format("[{}, {}]", spec.min, spec.max);
    case ParameterType::Bool: return "true|false";
    case ParameterType::Choice: return fmt::format("{}", fmt::join(spec.choices, "|"));
  }
  return "";
}

void run_techniques() {
  for (const TechniqueInfo& info : technique_registry()) {
    fmt::print("{}\n  {}\n", info.name, info.summary);
    for (const ParameterSpec& p : info.parameters.specs()) {
      fmt::print("    {:<22} {:<6} default {:<10} {:<22} {}\n", p.name, p.type_name(), to_string(p.default_value),
                 describe_range(p), p.doc);
    }
  }
}

}  // namespace

void add_techniques_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("techniques", "list the techniques with their parameters");
  cmd->callback(run_techniques);
}

}  // namespace penumbra::cli
