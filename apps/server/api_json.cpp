#include "server/api_json.h"

#include "penumbra/io/volume_reader.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/volume/procedural.h"

namespace penumbra::server {

using nlohmann::json;

namespace {

json value_json(const ParameterSpec& spec, const ParameterValue& value) {
  if (spec.type == ParameterType::Int) return int(std::get<double>(value));
  return std::visit([](const auto& v) { return json(v); }, value);
}

}  // namespace

json techniques_json() {
  json list = json::array();
  for (const TechniqueInfo& info : technique_registry()) {
    json parameters = json::array();
    for (const ParameterSpec& spec : info.parameters.specs()) {
      json p{{"name", spec.name}, {"type", spec.type_name()}, {"default", value_json(spec, spec.default_value)},
             {"doc", spec.doc}};
      if (spec.type == ParameterType::Float || spec.type == ParameterType::Int) {
        p["min"] = spec.min;
        p["max"] = spec.max;
      }
      if (spec.type == ParameterType::Choice) p["choices"] = spec.choices;
      parameters.push_back(std::move(p));
    }
    list.push_back({{"name", info.name}, {"summary", info.summary}, {"parameters", std::move(parameters)}});
  }
  return {{"techniques", std::move(list)}};
}

json volumes_json(const DataDirectory& data, int max_builtin_size) {
  json files = json::array();
  for (const DataEntry& e : data.list_volumes()) files.push_back({{"path", e.path}, {"bytes", e.bytes}});
  json builtins = json::array();
  for (const ProceduralInfo& p : procedural_volumes()) builtins.push_back({{"name", p.name}, {"doc", p.doc}});
  return {{"data_folder", data.available()},
          {"files", std::move(files)},
          {"builtins", std::move(builtins)},
          {"extensions", supported_volume_extensions()},
          {"max_builtin_size", max_builtin_size}};
}

}  // namespace penumbra::server
