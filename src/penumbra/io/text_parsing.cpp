#include "penumbra/io/text_parsing.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>

namespace penumbra {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

}  // namespace

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

std::string to_lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool equals_ignore_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](unsigned char x, unsigned char y) {
           return std::tolower(x) == std::tolower(y);
         });
}

std::vector<std::string_view> split_words(std::string_view text, std::string_view extra_separators) {
  std::vector<std::string_view> words;
  const auto separator = [&](char c) { return is_space(c) || extra_separators.find(c) != std::string_view::npos; };
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && separator(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !separator(text[i])) ++i;
    if (i > start) words.push_back(text.substr(start, i - start));
  }
  return words;
}

std::optional<std::int64_t> parse_int(std::string_view token) {
  token = trim(token);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
  return value;
}

std::optional<double> parse_double(std::string_view token) {
  token = trim(token);
  if (token.empty()) return std::nullopt;
  // strtod needs a terminated string and honours the C locale's decimal
  // point, which is "." unless someone called setlocale; file formats use ".".
  const std::string copy(token);
  char* end = nullptr;
  const double value = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size()) return std::nullopt;
  return value;
}

std::optional<std::vector<std::int64_t>> parse_ints(std::string_view text, std::string_view extra_separators) {
  std::vector<std::int64_t> values;
  for (std::string_view word : split_words(text, extra_separators)) {
    const auto v = parse_int(word);
    if (!v) return std::nullopt;
    values.push_back(*v);
  }
  return values;
}

std::optional<std::vector<double>> parse_doubles(std::string_view text, std::string_view extra_separators) {
  std::vector<double> values;
  for (std::string_view word : split_words(text, extra_separators)) {
    const auto v = parse_double(word);
    if (!v) return std::nullopt;
    values.push_back(*v);
  }
  return values;
}

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == text.size()) break;
    start = end + 1;
  }
  return lines;
}

}  // namespace penumbra
