#pragma once
// JSON bodies of the listing endpoints. The technique list is built from the
// registry's parameter tables only, so the viewer's controls for a technique
// added later appear without a change here or in the viewer.
#include "server/data_directory.h"

#include <nlohmann/json.hpp>

namespace penumbra::server {

// {"techniques": [{"name", "summary", "parameters": [{"name", "type"
// ("float" | "int" | "bool" | "choice"), "default", "min", "max", "choices",
// "doc"}]}]}; min/max only for float and int, choices only for choice.
nlohmann::json techniques_json();

// {"data_folder": bool, "files": [{"path", "bytes"}], "builtins": [{"name",
// "doc"}], "extensions": [...], "max_builtin_size": N}
nlohmann::json volumes_json(const DataDirectory& data, int max_builtin_size);

}  // namespace penumbra::server
