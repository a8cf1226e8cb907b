#include "penumbra/io/paraview_preset.h"

#include "penumbra/analysis/color_space.h"
#include "penumbra/base/error.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/xml_scanner.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {
namespace {

using json = nlohmann::json;

// A preset as the file states it, before conversion.
struct Preset {
  std::string name;
  std::vector<std::array<double, 4>> rgb;      // x, r, g, b (sRGB)
  std::vector<std::array<double, 4>> opacity;  // x, alpha, midpoint, sharpness
  bool has_rgb = false;
};

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw IoError(source, "ParaView preset: " + what);
}

std::vector<std::array<double, 4>> quadruples(const std::string& source, const Preset& preset, const json& values,
                                              const char* key) {
  if (!values.is_array()) fail(source, fmt::format("'{}' of preset '{}' is not an array", key, preset.name));
  if (values.empty() || values.size() % 4 != 0) {
    fail(source, fmt::format("'{}' of preset '{}' has {} numbers; it needs groups of 4", key, preset.name,
                             values.size()));
  }
  std::vector<std::array<double, 4>> out(values.size() / 4);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!values[i].is_number()) fail(source, fmt::format("'{}' of preset '{}' holds a non-number", key, preset.name));
    const double v = values[i].get<double>();
    if (!std::isfinite(v)) fail(source, fmt::format("'{}' of preset '{}' holds {}", key, preset.name, v));
    out[i / 4][i % 4] = v;
  }
  return out;
}

std::vector<Preset> presets_from_json(std::string_view text, const std::string& source) {
  json document;
  try {
    document = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond a double (1e400).
    fail(source, fmt::format("invalid JSON: {}", e.what()));
  }
  if (document.is_object()) document = json::array({document});
  if (!document.is_array()) fail(source, "expected an array of presets or one preset object");
  std::vector<Preset> presets;
  for (std::size_t i = 0; i < document.size(); ++i) {
    const json& object = document[i];
    if (!object.is_object()) fail(source, fmt::format("entry {} is not an object", i));
    Preset preset;
    const auto name = object.find("Name");
    preset.name = name != object.end() && name->is_string() ? name->get<std::string>() : fmt::format("#{}", i);
    if (const auto rgb = object.find("RGBPoints"); rgb != object.end()) {
      preset.rgb = quadruples(source, preset, *rgb, "RGBPoints");
      preset.has_rgb = true;
    }
    if (const auto points = object.find("Points"); points != object.end()) {
      preset.opacity = quadruples(source, preset, *points, "Points");
    }
    presets.push_back(std::move(preset));
  }
  return presets;
}

std::vector<Preset> presets_from_xml(std::string_view text, const std::string& source) {
  XmlScanner scanner(text, source);
  std::vector<Preset> presets;
  Preset* current = nullptr;
  while (auto tag = scanner.next()) {
    if (tag->name == "ColorMap" && tag->kind != XmlTag::Kind::End) {
      presets.emplace_back();
      current = &presets.back();
      const std::string* name = tag->attribute("name");
      current->name = name ? *name : fmt::format("#{}", presets.size() - 1);
    } else if (tag->name == "ColorMap") {
      current = nullptr;
    } else if (tag->name == "Point" && current) {
      const auto number = [&](const char* key) -> std::optional<double> {
        const std::string* value = tag->attribute(key);
        if (!value) return std::nullopt;
        const auto parsed = parse_double(*value);
        if (!parsed || !std::isfinite(*parsed)) {
          fail(source, fmt::format("attribute {}=\"{}\" in preset '{}' is not a number", key, *value, current->name));
        }
        return parsed;
      };
      const auto x = number("x");
      const auto r = number("r");
      const auto g = number("g");
      const auto b = number("b");
      if (!x || !r || !g || !b) fail(source, fmt::format("a <Point> of preset '{}' lacks x, r, g or b", current->name));
      current->rgb.push_back({*x, *r, *g, *b});
      current->has_rgb = true;
      if (const auto o = number("o")) current->opacity.push_back({*x, *o, 0.5, 0.0});
    }
  }
  return presets;
}

// Piecewise-linear function through (x, y) stops sorted by x, clamped at
// the ends.
double evaluate(const std::vector<std::array<double, 2>>& stops, double x) {
  if (x <= stops.front()[0]) return stops.front()[1];
  if (x >= stops.back()[0]) return stops.back()[1];
  const auto upper = std::upper_bound(stops.begin(), stops.end(), x,
                                      [](double value, const std::array<double, 2>& s) { return value < s[0]; });
  const auto& b = *upper;
  const auto& a = *(upper - 1);
  if (b[0] <= a[0]) return b[1];
  const double t = (x - a[0]) / (b[0] - a[0]);
  return a[1] + t * (b[1] - a[1]);
}

TransferFunction convert(const Preset& preset, const std::string& source) {
  std::vector<std::array<double, 4>> rgb = preset.rgb;
  std::stable_sort(rgb.begin(), rgb.end(), [](const auto& a, const auto& b) { return a[0] < b[0]; });
  const double lo = rgb.front()[0];
  const double hi = rgb.back()[0];
  const double width = hi - lo;
  const auto normalise = [&](double x) { return width > 0.0 ? (x - lo) / width : 0.0; };

  std::vector<std::array<double, 2>> channels[3];
  for (const auto& p : rgb) {
    for (int c = 0; c < 3; ++c) channels[c].push_back({normalise(p[0]), p[1 + c]});
  }
  std::vector<std::array<double, 2>> alpha;
  if (preset.opacity.empty()) {
    alpha = {{0.0, 0.0}, {1.0, 1.0}};
  } else {
    std::vector<std::array<double, 4>> opacity = preset.opacity;
    std::stable_sort(opacity.begin(), opacity.end(), [](const auto& a, const auto& b) { return a[0] < b[0]; });
    for (std::size_t i = 0; i < opacity.size(); ++i) {
      alpha.push_back({normalise(opacity[i][0]), opacity[i][1]});
      // ParaView's midpoint is where the segment reaches the average of its
      // end values; with sharpness 0 the curve is linear on either side.
      const double midpoint = opacity[i][2];
      if (i + 1 < opacity.size() && midpoint > 0.0 && midpoint < 1.0 && midpoint != 0.5) {
        const double x = opacity[i][0] + midpoint * (opacity[i + 1][0] - opacity[i][0]);
        alpha.push_back({normalise(x), 0.5 * (opacity[i][1] + opacity[i + 1][1])});
      }
    }
  }

  std::vector<double> positions = {0.0, 1.0};
  for (const auto& p : channels[0]) positions.push_back(p[0]);
  for (const auto& p : alpha) positions.push_back(p[0]);
  std::erase_if(positions, [](double x) { return !(x >= 0.0 && x <= 1.0); });
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end(), [](double a, double b) { return b - a < 1e-9; }),
                  positions.end());

  std::vector<TransferFunctionPoint> points;
  for (double x : positions) {
    // A zero-width preset is one colour; sample it at its only position.
    const double at = width > 0.0 ? x : 0.0;
    TransferFunctionPoint p;
    p.value = static_cast<float>(x);
    for (int c = 0; c < 3; ++c) p.color[c] = srgb_decode(static_cast<float>(evaluate(channels[c], at)));
    p.alpha = clamp01(static_cast<float>(preset.opacity.empty() ? x : evaluate(alpha, at)));
    points.push_back(p);
  }
  try {
    TransferFunction tf(std::move(points));
    tf.set_range(std::nullopt);
    return tf;
  } catch (const InvalidArgument& e) {
    fail(source, fmt::format("preset '{}' does not make a valid transfer function: {}", preset.name, e.what()));
  }
}

TransferFunction pick(const std::vector<Preset>& presets, std::string_view name, const std::string& source) {
  if (presets.empty()) fail(source, "the file holds no presets");
  for (const Preset& preset : presets) {
    if (name.empty() ? preset.has_rgb : preset.name == name) {
      if (!preset.has_rgb) fail(source, fmt::format("preset '{}' has no RGBPoints (indexed colour maps are not "
                                                    "supported)",
                                                    preset.name));
      return convert(preset, source);
    }
  }
  if (name.empty()) fail(source, "no preset has RGBPoints");
  std::vector<std::string> names;
  for (const Preset& preset : presets) {
    if (names.size() == 40) {
      names.push_back(fmt::format("... ({} more)", presets.size() - 40));
      break;
    }
    names.push_back("'" + preset.name + "'");
  }
  fail(source, fmt::format("no preset named '{}'; the file has {}", name, fmt::join(names, ", ")));
}

bool is_xml(const std::filesystem::path& path) { return to_lower(path.extension().string()) == ".xml"; }

std::vector<Preset> presets_from_file(const std::filesystem::path& path) {
  const std::uint64_t size = file_size_checked(path);
  if (size > (64u << 20)) fail(display_path(path), fmt::format("{} bytes is too large for a preset file", size));
  const std::string text = read_text_file(path);
  return is_xml(path) ? presets_from_xml(text, display_path(path)) : presets_from_json(text, display_path(path));
}

}  // namespace

TransferFunction parse_paraview_preset(std::string_view json_text, std::string_view name, const std::string& source) {
  return pick(presets_from_json(json_text, source), name, source);
}

TransferFunction read_paraview_preset(const std::filesystem::path& path, std::string_view name) {
  return pick(presets_from_file(path), name, display_path(path));
}

std::vector<std::string> paraview_preset_names(const std::filesystem::path& path) {
  std::vector<std::string> names;
  for (const Preset& preset : presets_from_file(path)) names.push_back(preset.name);
  return names;
}

}  // namespace penumbra
