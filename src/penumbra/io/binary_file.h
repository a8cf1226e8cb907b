#pragma once
// Whole-file and ranged reads with the checks every reader needs: the file
// exists, is a regular file, and holds the bytes a header promises, all
// checked before anything is allocated. Failures throw IoError naming the path.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace penumbra {

// Size of a regular file; IoError if it is missing or not a regular file.
std::uint64_t file_size_checked(const std::filesystem::path& path);

// The whole file, after checking its size against the memory budget.
std::vector<std::byte> read_whole_file(const std::filesystem::path& path);
std::string read_text_file(const std::filesystem::path& path);

// Reads exactly out.size() bytes starting at `offset`; IoError naming `what`
// (e.g. "voxel data") when the file is shorter.
void read_file_range(const std::filesystem::path& path, std::uint64_t offset, std::span<std::byte> out,
                     const std::string& what);

// Writes the bytes, replacing the file; IoError on failure.
void write_whole_file(const std::filesystem::path& path, std::span<const std::byte> bytes);

// Paths in error messages and Volume::source read as the user typed them.
std::string display_path(const std::filesystem::path& path);

}  // namespace penumbra
