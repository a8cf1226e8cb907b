#include "penumbra/io/nifti_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/byte_order.h"
#include "penumbra/io/compression.h"
#include "penumbra/io/volume_layout.h"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace penumbra {
namespace {

constexpr std::size_t kHeaderBytes = 348;
constexpr std::int32_t kNifti2HeaderBytes = 540;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw IoError(display_path(path), "NIfTI header: " + what);
}

// Reads fields of the raw header at their NIfTI-1 byte offsets, in the
// header's byte order.
class HeaderFields {
 public:
  HeaderFields(const std::array<std::byte, kHeaderBytes>& bytes, std::endian order) : bytes_(bytes), order_(order) {}

  template <class T> T get(std::size_t offset) const {
    std::array<std::byte, sizeof(T)> raw;
    std::memcpy(raw.data(), bytes_.data() + offset, sizeof(T));
    convert_byte_order(raw, sizeof(T), order_);
    return std::bit_cast<T>(raw);
  }
  std::int16_t i16(std::size_t offset) const { return get<std::int16_t>(offset); }
  float f32(std::size_t offset) const { return get<float>(offset); }

 private:
  const std::array<std::byte, kHeaderBytes>& bytes_;
  std::endian order_;
};

std::optional<VoxelType> nifti_type(std::int16_t datatype) {
  switch (datatype) {
    case 2: return VoxelType::UInt8;
    case 4: return VoxelType::Int16;
    case 8: return VoxelType::Int32;
    case 16: return VoxelType::Float32;
    case 64: return VoxelType::Float64;
    case 256: return VoxelType::Int8;
    case 512: return VoxelType::UInt16;
    case 768: return VoxelType::UInt32;
    default: return std::nullopt;
  }
}

bool is_gzip_path(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  return name.size() > 3 && (name.ends_with(".gz") || name.ends_with(".GZ"));
}

// Replaces `volume` by a float32 copy holding value * slope + intercept.
std::shared_ptr<Volume> apply_scaling(const Volume& volume, float slope, float intercept) {
  auto scaled = std::make_shared<Volume>(volume.dims(), VoxelType::Float32, volume.frame_count());
  for (int f = 0; f < volume.frame_count(); ++f) {
    float* out = scaled->frame_as<float>(f);
    const std::byte* in = volume.frame_data(f);
    visit_voxel_type(volume.type(), [&](auto tag) {
      using T = decltype(tag);
      const T* values = reinterpret_cast<const T*>(in);
      parallel_for(0, static_cast<std::int64_t>(volume.voxel_count()), [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t i = first; i < last; ++i) out[i] = static_cast<float>(values[i]) * slope + intercept;
      }, 1 << 16);
    });
  }
  scaled->set_spacing(volume.spacing());
  scaled->set_origin(volume.origin());
  scaled->set_source(volume.source());
  return scaled;
}

}  // namespace

std::shared_ptr<Volume> read_nifti(const std::filesystem::path& path) {
  const bool gzipped = is_gzip_path(path);
  std::array<std::byte, kHeaderBytes> bytes;
  if (gzipped) {
    InflateStream(path, 0).read_exact(bytes, "NIfTI header");
  } else {
    read_file_range(path, 0, bytes, "NIfTI header");
  }

  std::int32_t sizeof_hdr = 0;
  std::memcpy(&sizeof_hdr, bytes.data(), 4);
  std::endian order = std::endian::native;
  if (sizeof_hdr != static_cast<std::int32_t>(kHeaderBytes)) {
    std::array<std::byte, 4> raw;
    std::memcpy(raw.data(), bytes.data(), 4);
    swap_bytes(raw, 4);
    const std::int32_t swapped = std::bit_cast<std::int32_t>(raw);
    if (swapped == static_cast<std::int32_t>(kHeaderBytes)) {
      order = std::endian::native == std::endian::little ? std::endian::big : std::endian::little;
    } else if (sizeof_hdr == kNifti2HeaderBytes || swapped == kNifti2HeaderBytes) {
      fail(path, "this is a NIfTI-2 file; penumbra reads NIfTI-1");
    } else {
      fail(path, fmt::format("sizeof_hdr is {}, not 348 in either byte order; not a NIfTI-1 file", sizeof_hdr));
    }
  }
  const HeaderFields header(bytes, order);
  const char* magic = reinterpret_cast<const char*>(bytes.data() + 344);
  if (std::memcmp(magic, "ni1\0", 4) == 0) {
    fail(path, "this is the header of a .hdr/.img pair; penumbra reads single-file .nii");
  }
  if (std::memcmp(magic, "n+1\0", 4) != 0) fail(path, "the magic is not 'n+1'; not a single-file NIfTI-1");

  std::array<std::int16_t, 8> dim;
  for (std::size_t i = 0; i < 8; ++i) dim[i] = header.i16(40 + 2 * i);
  if (dim[0] < 3 || dim[0] > 7) {
    fail(path, fmt::format("dim[0] is {}; penumbra reads 3D volumes and 4D time series", dim[0]));
  }
  for (int i = 1; i <= dim[0]; ++i) {
    if (dim[static_cast<std::size_t>(i)] <= 0) fail(path, fmt::format("dim[{}] is {}; it must be positive", i, dim[static_cast<std::size_t>(i)]));
    if (i > 4 && dim[static_cast<std::size_t>(i)] != 1) {
      fail(path, fmt::format("dim[{}] is {}; dimensions beyond time are not supported", i, dim[static_cast<std::size_t>(i)]));
    }
  }
  VolumeLayout layout;
  layout.byte_order = order;
  layout.dims = ivec3(dim[1], dim[2], dim[3]);
  layout.frame_count = dim[0] >= 4 ? dim[4] : 1;

  const std::int16_t datatype = header.i16(70);
  const auto type = nifti_type(datatype);
  if (!type) {
    fail(path, fmt::format("datatype {} is not supported (uint8, int8, int16, uint16, int32, uint32, float32 and "
                           "float64 are)",
                           datatype));
  }
  layout.type = *type;

  for (int a = 0; a < 3; ++a) {
    const float p = std::fabs(header.f32(76 + 4 * static_cast<std::size_t>(a + 1)));
    // pixdim 0 or NaN means "unknown" in files in the wild (2D images and
    // some converters write them): unit spacing. A negative pixdim keeps its
    // magnitude (the orientation lives in qfac and the forms); an infinite
    // or subnormal one is an error.
    if (std::isinf(p) || (p > 0.0f && p < std::numeric_limits<float>::min())) {
      fail(path, fmt::format("pixdim[{}] is {}; a spacing must be finite and a normal float", a + 1,
                             header.f32(76 + 4 * static_cast<std::size_t>(a + 1))));
    }
    layout.spacing[a] = p > 0.0f ? p : 1.0f;
  }

  const float qfac = header.f32(76);
  const std::int16_t qform_code = header.i16(252);
  const std::int16_t sform_code = header.i16(254);
  if (sform_code > 0) {
    std::array<float, 12> srow;
    for (std::size_t i = 0; i < 12; ++i) srow[i] = header.f32(280 + 4 * i);
    const bool axis_aligned = srow[0] > 0.0f && srow[5] > 0.0f && srow[10] > 0.0f && srow[1] == 0.0f &&
                              srow[2] == 0.0f && srow[4] == 0.0f && srow[6] == 0.0f && srow[8] == 0.0f &&
                              srow[9] == 0.0f;
    if (axis_aligned) layout.origin = vec3(srow[3], srow[7], srow[11]);
  } else if (qform_code > 0) {
    const bool identity_rotation = header.f32(256) == 0.0f && header.f32(260) == 0.0f && header.f32(264) == 0.0f;
    if (identity_rotation && qfac >= 0.0f) layout.origin = vec3(header.f32(268), header.f32(272), header.f32(276));
  }
  if (layout.origin && !(std::isfinite(layout.origin->x) && std::isfinite(layout.origin->y) &&
                         std::isfinite(layout.origin->z))) {
    layout.origin.reset();
  }

  const float vox_offset = header.f32(108);
  if (!std::isfinite(vox_offset) || vox_offset < static_cast<float>(kHeaderBytes) || vox_offset > 1e12f) {
    fail(path, fmt::format("vox_offset is {}; it must be at least 348", vox_offset));
  }
  PayloadSource source;
  source.file = path;
  if (gzipped) {
    source.encoding = PayloadEncoding::Compressed;
    source.skip_after_decoding = static_cast<std::uint64_t>(vox_offset);
  } else {
    source.offset = static_cast<std::uint64_t>(vox_offset);
  }
  std::shared_ptr<Volume> volume = load_volume(path, layout, {source});

  const float slope = header.f32(112);
  const float intercept = header.f32(116);
  const bool scaled = slope != 0.0f && std::isfinite(slope) && std::isfinite(intercept) &&
                      !(slope == 1.0f && intercept == 0.0f);
  if (scaled) volume = apply_scaling(*volume, slope, intercept);
  return volume;
}

}  // namespace penumbra
