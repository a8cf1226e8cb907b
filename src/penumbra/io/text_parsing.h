#pragma once
// Small strict parsers for the text headers of volume formats (NRRD, .dat,
// MetaImage, VTK XML attributes). Strict means "the whole token is a number":
// "12abc" is not 12, so a malformed header is reported rather than guessed.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

std::string_view trim(std::string_view text);
std::string to_lower(std::string_view text);
bool equals_ignore_case(std::string_view a, std::string_view b);

// Splits at runs of whitespace (and at `extra` separator characters).
std::vector<std::string_view> split_words(std::string_view text, std::string_view extra_separators = {});

std::optional<std::int64_t> parse_int(std::string_view token);
// Accepts what strtod accepts, including "nan" and "inf", but the whole
// token must be consumed.
std::optional<double> parse_double(std::string_view token);

// Parses every word of `text` as a number; nullopt if any word is not one.
std::optional<std::vector<std::int64_t>> parse_ints(std::string_view text, std::string_view extra_separators = {});
std::optional<std::vector<double>> parse_doubles(std::string_view text, std::string_view extra_separators = {});

// Splits text into lines at \n, dropping a trailing \r.
std::vector<std::string_view> split_lines(std::string_view text);

}  // namespace penumbra
