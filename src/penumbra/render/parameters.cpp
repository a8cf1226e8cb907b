#include "penumbra/render/parameters.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace penumbra {

ParameterSpec ParameterSpec::real(std::string name, double def, double min, double max, std::string doc) {
  return ParameterSpec{std::move(name), ParameterType::Float, def, min, max, {}, std::move(doc)};
}

ParameterSpec ParameterSpec::integer(std::string name, int def, int min, int max, std::string doc) {
  return ParameterSpec{std::move(name), ParameterType::Int, double(def), double(min), double(max), {}, std::move(doc)};
}

ParameterSpec ParameterSpec::flag(std::string name, bool def, std::string doc) {
  return ParameterSpec{std::move(name), ParameterType::Bool, def, 0.0, 1.0, {}, std::move(doc)};
}

ParameterSpec ParameterSpec::choice(std::string name, std::string def, std::vector<std::string> choices,
                                    std::string doc) {
  return ParameterSpec{std::move(name), ParameterType::Choice, std::move(def), 0.0, 0.0, std::move(choices),
                       std::move(doc)};
}

std::string ParameterSpec::type_name() const {
  switch (type) {
    case ParameterType::Float: return "float";
    case ParameterType::Int: return "int";
    case ParameterType::Bool: return "bool";
    case ParameterType::Choice: return "choice";
  }
  return "?";
}

std::string to_string(const ParameterValue& value) {
  if (const double* d = std::get_if<double>(&value)) return fmt::format("{}", *d);
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  return std::get<std::string>(value);
}

ParameterValue ParameterSpec::validate(const ParameterValue& value) const {
  switch (type) {
    case ParameterType::Float:
    case ParameterType::Int: {
      const double* d = std::get_if<double>(&value);
      if (!d) throw InvalidArgument(name, fmt::format("expects a number, got '{}'", to_string(value)));
      if (!std::isfinite(*d)) throw InvalidArgument(name, "must be a finite number");
      if (type == ParameterType::Int && *d != std::floor(*d)) {
        throw InvalidArgument(name, fmt::format("expects an integer, got {}", *d));
      }
      if (*d < min || *d > max) {
        throw InvalidArgument(name, fmt::format("{} is outside the range [{}, {}]", *d, min, max));
      }
      return *d;
    }
    case ParameterType::Bool:
      if (!std::holds_alternative<bool>(value)) {
        throw InvalidArgument(name, fmt::format("expects true or false, got '{}'", to_string(value)));
      }
      return value;
    case ParameterType::Choice: {
      const std::string* s = std::get_if<std::string>(&value);
      if (s) {
        for (const std::string& c : choices) {
          if (c == *s) return value;
        }
      }
      throw InvalidArgument(name, fmt::format("'{}' is not one of: {}", to_string(value), fmt::join(choices, ", ")));
    }
  }
  return value;
}

ParameterValue ParameterSpec::parse(std::string_view text) const {
  switch (type) {
    case ParameterType::Float:
    case ParameterType::Int: {
      double d = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), d);
      if (ec != std::errc() || end != text.data() + text.size()) {
        throw InvalidArgument(name, fmt::format("expects a number, got '{}'", text));
      }
      return validate(d);
    }
    case ParameterType::Bool:
      if (text == "true" || text == "on" || text == "1") return true;
      if (text == "false" || text == "off" || text == "0") return false;
      throw InvalidArgument(name, fmt::format("expects true/false (or on/off), got '{}'", text));
    case ParameterType::Choice: return validate(std::string(text));
  }
  return std::string(text);
}

ParameterTable::ParameterTable(std::vector<ParameterSpec> specs) : specs_(std::move(specs)) {}

const ParameterSpec* ParameterTable::find(std::string_view name) const {
  for (const ParameterSpec& s : specs_) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const ParameterSpec& ParameterTable::at(std::string_view name) const {
  if (const ParameterSpec* s = find(name)) return *s;
  std::vector<std::string> names;
  for (const ParameterSpec& s : specs_) names.push_back(s.name);
  throw InvalidArgument(std::string(name),
                        names.empty() ? std::string("unknown parameter: this technique has no parameters")
                                      : fmt::format("unknown parameter (known: {})", fmt::join(names, ", ")));
}

ParameterValues::ParameterValues(const ParameterTable& table) : table_(table) {
  for (const ParameterSpec& s : table_.specs()) values_.push_back(s.default_value);
}

std::size_t ParameterValues::index_of(std::string_view name) const {
  const ParameterSpec& spec = table_.at(name);
  return static_cast<std::size_t>(&spec - table_.specs().data());
}

void ParameterValues::set(std::string_view name, const ParameterValue& value) {
  const std::size_t i = index_of(name);
  values_[i] = table_.specs()[i].validate(value);
}

void ParameterValues::apply(const ParameterSettings& settings, bool strict, std::string_view technique) {
  for (const auto& [key, value] : settings) {
    std::string_view name = key;
    bool targeted = false;
    if (const auto dot = name.find('.'); dot != std::string_view::npos) {
      if (name.substr(0, dot) != technique) continue;  // another technique's
      name = name.substr(dot + 1);
      targeted = true;
    }
    if (targeted || strict) {
      set(name, value);  // throws naming the parameter
      continue;
    }
    if (!table_.find(name)) continue;
    // A flat name meant for another technique that shares the name but not
    // the values (pathtrace's and occlusion-map's "mode").
    try {
      set(name, value);
    } catch (const InvalidArgument&) {
    }
  }
}

const ParameterValue& ParameterValues::value(std::string_view name) const { return values_[index_of(name)]; }

double ParameterValues::number(std::string_view name) const {
  const ParameterValue& v = value(name);
  if (const double* d = std::get_if<double>(&v)) return *d;
  throw InvalidArgument(std::string(name), "is not a number parameter");
}

int ParameterValues::integer(std::string_view name) const { return static_cast<int>(number(name)); }

bool ParameterValues::flag(std::string_view name) const {
  const ParameterValue& v = value(name);
  if (const bool* b = std::get_if<bool>(&v)) return *b;
  throw InvalidArgument(std::string(name), "is not a true/false parameter");
}

const std::string& ParameterValues::choice(std::string_view name) const {
  const ParameterValue& v = value(name);
  if (const std::string* s = std::get_if<std::string>(&v)) return *s;
  throw InvalidArgument(std::string(name), "is not a choice parameter");
}

}  // namespace penumbra
