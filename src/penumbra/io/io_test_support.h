#pragma once
// Helpers for the io tests: a per-test temporary folder, files written from
// bytes or text, volumes filled with values that exercise a type's range, and
// the location of the real data in ../shared/data.
#include "penumbra/base/error.h"
#include "penumbra/io/byte_order.h"
#include "penumbra/io/compression.h"
#include "penumbra/volume/volume.h"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

namespace penumbra::test {

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "io";
    path_ = std::filesystem::temp_directory_path() /
            ("penumbra_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + name);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline void write_file(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  // Removing first avoids ext4 flushing a file that is truncated and
  // rewritten (auto_da_alloc), which made rewriting tests slow.
  std::error_code ec;
  std::filesystem::remove(path, ec);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

inline void write_file(const std::filesystem::path& path, std::string_view text) {
  write_file(path, std::as_bytes(std::span(text.data(), text.size())));
}

inline std::vector<std::byte> concat(std::initializer_list<std::span<const std::byte>> parts) {
  std::vector<std::byte> out;
  for (auto part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

inline std::span<const std::byte> text_bytes(std::string_view text) {
  return std::as_bytes(std::span(text.data(), text.size()));
}

inline std::vector<std::byte> gzip(std::span<const std::byte> data) {
  return deflate_bytes(data, CompressionFormat::Gzip);
}

// Values spread over the type's range (negative ones for signed types,
// fractions for floats), different in every voxel and frame.
template <class T> T test_value(std::uint64_t i) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<T>(static_cast<double>(i) * 0.37 - 100.25);
  } else {
    const std::uint64_t span = std::uint64_t(std::numeric_limits<T>::max()) - std::int64_t(std::numeric_limits<T>::min());
    const std::uint64_t step = span / 97 + 1;
    return static_cast<T>(std::int64_t(std::numeric_limits<T>::min()) + std::int64_t((i * step) % (span + 1)));
  }
}

inline std::shared_ptr<Volume> make_volume(ivec3 dims, VoxelType type, int frames = 1) {
  auto volume = std::make_shared<Volume>(dims, type, frames);
  for (int f = 0; f < frames; ++f) {
    visit_voxel_type(type, [&](auto tag) {
      using T = decltype(tag);
      T* data = volume->frame_as<T>(f);
      for (std::uint64_t i = 0; i < volume->voxel_count(); ++i) data[i] = test_value<T>(i + 1000 * std::uint64_t(f));
    });
  }
  return volume;
}

// The voxels of `volume` as a file would hold them in `order`.
inline std::vector<std::byte> voxel_file_bytes(const Volume& volume, std::endian order) {
  std::vector<std::byte> bytes;
  for (int f = 0; f < volume.frame_count(); ++f) {
    const std::byte* data = volume.frame_data(f);
    bytes.insert(bytes.end(), data, data + volume.frame_bytes());
  }
  convert_byte_order(bytes, voxel_size(volume.type()), order);
  return bytes;
}

inline void expect_same_voxels(const Volume& expected, const Volume& actual) {
  ASSERT_EQ(expected.dims(), actual.dims());
  ASSERT_EQ(expected.type(), actual.type());
  ASSERT_EQ(expected.frame_count(), actual.frame_count());
  for (int f = 0; f < expected.frame_count(); ++f) {
    EXPECT_EQ(0, std::memcmp(expected.frame_data(f), actual.frame_data(f), expected.frame_bytes())) << "frame " << f;
  }
}

// Runs `read` and expects an IoError whose message contains `fragment`.
inline void expect_io_error(const std::function<void()>& read, std::string_view fragment) {
  try {
    read();
    ADD_FAILURE() << "expected IoError containing \"" << fragment << "\"";
  } catch (const IoError& e) {
    EXPECT_NE(std::string_view(e.what()).find(fragment), std::string_view::npos)
        << "message: " << e.what() << "\nexpected to contain: " << fragment;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected IoError, got: " << e.what();
  }
}

// Builds a NIfTI-1 header field by field at the offsets of the standard.
class NiftiHeader {
 public:
  explicit NiftiHeader(std::endian order) : order_(order) {
    put<std::int32_t>(0, 348);
    put<float>(108, 352.0f);  // vox_offset
    std::memcpy(bytes_.data() + 344, "n+1\0", 4);
  }
  template <class T> NiftiHeader& put(std::size_t offset, T value) {
    std::byte raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    convert_byte_order(std::span(raw, sizeof(T)), sizeof(T), order_);
    std::memcpy(bytes_.data() + offset, raw, sizeof(T));
    return *this;
  }
  NiftiHeader& dims(std::initializer_list<std::int16_t> d) {
    put<std::int16_t>(40, static_cast<std::int16_t>(d.size()));
    std::size_t i = 1;
    for (std::int16_t v : d) put<std::int16_t>(40 + 2 * i++, v);
    for (; i < 8; ++i) put<std::int16_t>(40 + 2 * i, 1);
    return *this;
  }
  NiftiHeader& datatype(std::int16_t code) { return put<std::int16_t>(70, code); }
  NiftiHeader& pixdim(float x, float y, float z) { return put<float>(80, x).put<float>(84, y).put<float>(88, z); }
  NiftiHeader& scaling(float slope, float intercept) { return put<float>(112, slope).put<float>(116, intercept); }
  NiftiHeader& sform(std::array<float, 12> rows) {
    put<std::int16_t>(254, 4);
    for (std::size_t i = 0; i < 12; ++i) put<float>(280 + 4 * i, rows[i]);
    return *this;
  }
  // Header, the 4-byte extension flag, then the voxels.
  std::vector<std::byte> file(std::span<const std::byte> voxels) const {
    return test::concat({bytes_, std::vector<std::byte>(4), voxels});
  }

 private:
  std::endian order_;
  std::array<std::byte, 348> bytes_{};
};

inline std::filesystem::path shared_data_dir() { return PENUMBRA_SHARED_DATA_DIR; }

}  // namespace penumbra::test
