#pragma once
// The registry of techniques: name -> summary, parameter table and factory.
// The CLI, the scene loader, the server and the benchmarks find techniques
// only through it, so a new technique appears everywhere once listed here.
#include "penumbra/render/technique.h"

#include <string_view>
#include <vector>

namespace penumbra {

const std::vector<TechniqueInfo>& technique_registry();

// Throws InvalidArgument("technique", ...) listing the known names.
const TechniqueInfo& find_technique(std::string_view name);

// Throws InvalidScene("render.params.<prefix>") for a "technique.name" key
// whose prefix names no technique (a per-technique object in scene JSON).
void check_technique_prefixes(const ParameterSettings& settings);

}  // namespace penumbra
