#pragma once
// Technique parameters. Each technique declares its parameters once, in a
// ParameterTable (name, type, default, range, one-line doc); that table is the
// single source for the CLI (--param k=v, `penumbra techniques`), scene JSON
// (render.params), the server UI and the docs. Lookups by a name the table
// does not declare are programming errors and throw, so a typo can never
// silently fall back to a default.
#include "penumbra/scene/scene.h"

#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

enum class ParameterType { Float, Int, Bool, Choice };

struct ParameterSpec {
  std::string name;
  ParameterType type = ParameterType::Float;
  ParameterValue default_value;
  double min = 0.0;  // inclusive range for Float and Int
  double max = 0.0;
  std::vector<std::string> choices;  // for Choice
  std::string doc;

  static ParameterSpec real(std::string name, double def, double min, double max, std::string doc);
  static ParameterSpec integer(std::string name, int def, int min, int max, std::string doc);
  static ParameterSpec flag(std::string name, bool def, std::string doc);
  static ParameterSpec choice(std::string name, std::string def, std::vector<std::string> choices, std::string doc);

  // Checks type and range; converts integral doubles for Int. Throws
  // InvalidArgument naming the parameter.
  ParameterValue validate(const ParameterValue& value) const;
  // Parses command-line text ("9", "true", "gaussian") for this parameter.
  ParameterValue parse(std::string_view text) const;
  std::string type_name() const;
};

std::string to_string(const ParameterValue& value);

class ParameterTable {
 public:
  ParameterTable() = default;
  ParameterTable(std::vector<ParameterSpec> specs);

  const std::vector<ParameterSpec>& specs() const { return specs_; }
  const ParameterSpec* find(std::string_view name) const;
  const ParameterSpec& at(std::string_view name) const;  // throws InvalidArgument

 private:
  std::vector<ParameterSpec> specs_;
};

// A complete, validated set of values for one table (defaults filled in).
class ParameterValues {
 public:
  ParameterValues() = default;
  explicit ParameterValues(const ParameterTable& table);

  // Sets a declared parameter after validation; throws InvalidArgument for an
  // unknown name (listing the known ones) or a bad value.
  void set(std::string_view name, const ParameterValue& value);
  // Applies settings. "technique.name" keys (scene JSON's per-technique
  // objects in render.params) apply only when the prefix is `technique`, and
  // then strictly. With `strict`, flat names the table does not declare or
  // whose value it refuses are an error; otherwise they are skipped
  // (settings written for another technique).
  void apply(const ParameterSettings& settings, bool strict, std::string_view technique = {});

  double number(std::string_view name) const;
  int integer(std::string_view name) const;
  bool flag(std::string_view name) const;
  const std::string& choice(std::string_view name) const;
  const ParameterValue& value(std::string_view name) const;

  const ParameterTable& table() const { return table_; }
  const std::vector<ParameterValue>& values() const { return values_; }
  bool operator==(const ParameterValues& other) const { return values_ == other.values_; }

 private:
  std::size_t index_of(std::string_view name) const;

  ParameterTable table_;
  std::vector<ParameterValue> values_;
};

}  // namespace penumbra
