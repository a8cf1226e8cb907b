#include "penumbra/io/file_pattern.h"

#include <fmt/format.h>

namespace penumbra {

std::optional<std::vector<std::string>> expand_file_pattern(std::string_view pattern, std::int64_t first,
                                                            std::int64_t last, std::int64_t step,
                                                            std::uint64_t max_count, std::string& error) {
  std::string prefix;
  std::string suffix;
  std::string flags;
  int width = 0;
  int conversions = 0;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    std::string& out = conversions == 0 ? prefix : suffix;
    if (pattern[i] != '%') {
      out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < pattern.size() && std::string_view("0-+ ").find(pattern[j]) != std::string_view::npos) {
      flags += pattern[j++];
    }
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9' && width < 1000) {
      width = width * 10 + (pattern[j++] - '0');
    }
    if (j >= pattern.size() || std::string_view("diu").find(pattern[j]) == std::string_view::npos) {
      error = fmt::format("pattern '{}' must use an integer conversion such as %03d", pattern);
      return std::nullopt;
    }
    ++conversions;
    i = j;
  }
  if (conversions != 1 || width >= 1000) {
    error = fmt::format("pattern '{}' must contain exactly one integer conversion such as %03d", pattern);
    return std::nullopt;
  }
  if (step == 0) {
    error = "pattern step must not be 0";
    return std::nullopt;
  }
  // Ranges are inclusive and may count down with a negative step.
  if ((last - first) / step < 0 || (last != first && (last > first) != (step > 0))) {
    error = fmt::format("pattern range {} to {} with step {} is empty", first, last, step);
    return std::nullopt;
  }
  const std::uint64_t count = static_cast<std::uint64_t>((last - first) / step) + 1;
  if (count > max_count) {
    error = fmt::format("pattern gives {} files ({} to {} step {}), but {} are needed", count, first, last, step,
                        max_count);
    return std::nullopt;
  }
  const bool left = flags.find('-') != std::string::npos;
  const bool zero = !left && flags.find('0') != std::string::npos;
  const bool plus = flags.find('+') != std::string::npos;
  std::vector<std::string> names;
  names.reserve(static_cast<std::size_t>(count));
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::int64_t index = first + static_cast<std::int64_t>(k) * step;
    std::string number = plus && index >= 0 ? fmt::format("+{}", index) : fmt::format("{}", index);
    if (static_cast<int>(number.size()) < width) {
      const std::size_t pad = static_cast<std::size_t>(width) - number.size();
      if (left) {
        number.append(pad, ' ');
      } else if (zero) {
        const std::size_t sign = (number[0] == '-' || number[0] == '+') ? 1 : 0;
        number.insert(sign, pad, '0');
      } else {
        number.insert(0, pad, ' ');
      }
    }
    names.push_back(prefix + number + suffix);
  }
  return names;
}

}  // namespace penumbra
