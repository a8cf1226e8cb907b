#pragma once
// File-name patterns of series headers: "vf_t%03d.raw.gz 1 91 10" names
// vf_t001.raw.gz, vf_t011.raw.gz, ... vf_t091.raw.gz (NRRD "data file",
// MetaImage "ElementDataFile"). The pattern is parsed here rather than passed
// to printf, so a header cannot smuggle in other conversions.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

// The names for first, first + step, ... up to and including last; nullopt
// with `error` set when the pattern has not exactly one integer conversion
// (%d, %i, %u with optional flags 0 - + and a width), step is 0, the range is
// empty, or it would give more than max_count names.
std::optional<std::vector<std::string>> expand_file_pattern(std::string_view pattern, std::int64_t first,
                                                            std::int64_t last, std::int64_t step,
                                                            std::uint64_t max_count, std::string& error);

}  // namespace penumbra
