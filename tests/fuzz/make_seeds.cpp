// fuzz_make_seeds OUT SHARED_DATA SCENES: writes the seed corpora OUT/<harness>/
// from the real volumes in ../shared/data (cropped to a few hundred voxels and
// written in every format and encoding the readers take, or their real headers
// pointed at the fixture files) and the repository's scenes (pointed at the
// fixture volume, mesh and preset). scripts/fuzz.sh runs it before fuzzing.
#include "harness.h"

#include "penumbra/base/memory_budget.h"
#include "penumbra/io/compression.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/io/volume_writer.h"
#include "penumbra/scene/mesh_shapes.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using namespace penumbra;
using nlohmann::json;

namespace {

fs::path g_out;
int g_count = 0;

void seed(const std::string& harness, const std::string& name, std::string_view bytes) {
  fs::create_directories(g_out / harness);
  std::ofstream(g_out / harness / name, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  ++g_count;
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string bytes_text(std::span<const std::byte> b) { return {reinterpret_cast<const char*>(b.data()), b.size()}; }

// The centre block of `v`, at most 8x8x6 voxels, with v's type and spacing.
std::shared_ptr<Volume> crop(const Volume& v) {
  const ivec3 d = glm::min(v.dims(), ivec3(8, 8, 6));
  const ivec3 o = (v.dims() - d) / 2;
  auto out = std::make_shared<Volume>(d, v.type());
  const std::size_t s = voxel_size(v.type());
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y) {
      const std::size_t from = ((std::size_t(o.z + z) * v.dims().y + (o.y + y)) * v.dims().x + o.x) * s;
      std::memcpy(out->frame_data(0) + (std::size_t(z) * d.y + y) * d.x * s, v.frame_data(0) + from, d.x * s);
    }
  out->set_spacing(v.spacing());
  return out;
}

std::string written(const std::function<void(const fs::path&)>& write, const std::string& ext) {
  const fs::path p = penumbra::fuzz::fixture_dir() / ("seed" + ext);
  write(p);
  return file_text(p);
}

bool is_header(const std::string& name) {
  for (const char* ext : {".nhdr", ".nrrd", ".nii.gz"}) {
    if (name.ends_with(ext)) return true;
  }
  return false;
}

// NRRD and MetaImage headers that name the fixture's data files.
void detached_seeds() {
  const char* nrrd_head = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nspacings: 1 1.5 2\n";
  seed("nrrd", "detached_raw.nhdr", std::string(nrrd_head) + "encoding: raw\ndata file: data.raw\n");
  seed("nrrd", "detached_gzip.nhdr", std::string(nrrd_head) + "encoding: gzip\ndata file: data.raw.gz\n");
  seed("nrrd", "detached_skip.nhdr", std::string(nrrd_head) + "encoding: raw\nline skip: 2\nbyte skip: 7\ndata file: data.raw\n");
  seed("nrrd", "detached_list.nhdr",
       "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\ndata file: LIST\n"
       "slice000.raw\nslice001.raw\nslice002.raw\nslice003.raw\nslice004.raw\nslice005.raw\nslice006.raw\nslice007.raw\n");
  seed("nrrd", "detached_pattern.nhdr",
       "NRRD0004\ntype: short\ndimension: 4\nsizes: 4 4 4 8\nendian: big\nencoding: raw\n"
       "data file: slice%03d.raw 0 7 1 3\nspace origin: (1,2,3)\nspace directions: (1,0,0) (0,1,0) (0,0,2) none\n");
  const char* mhd_head = "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementSpacing = 1 1 2\n";
  seed("metaimage", "detached_raw.mhd", std::string(mhd_head) + "ElementType = MET_UCHAR\nElementDataFile = data.raw\n");
  seed("metaimage", "detached_zlib.mhd",
       std::string(mhd_head) + "CompressedData = True\nElementType = MET_USHORT\nBinaryDataByteOrderMSB = True\n"
                               "ElementDataFile = data.zraw\n");
  seed("metaimage", "detached_list.mhd",
       std::string(mhd_head) + "ElementType = MET_UCHAR\nElementDataFile = LIST 2D\n"
                               "slice000.raw\nslice001.raw\nslice002.raw\nslice003.raw\nslice004.raw\nslice005.raw\n"
                               "slice006.raw\nslice007.raw\n");
  seed("metaimage", "detached_pattern.mhd",
       "NDims = 4\nDimSize = 4 4 4 4\nOffset = 1 2 3 0\nHeaderSize = -1\nElementType = MET_SHORT\n"
       "ElementDataFile = slice%03d.raw 0 3 1 3\n");
  for (const char* format : {"UCHAR", "USHORT", "SHORT", "FLOAT", "UINT8", "FLOAT64"}) {
    seed("dat", fmt::format("dat_{}.dat", format),
         fmt::format("ObjectFileName: data.raw\nTaggedFileName: ---\nResolution: 8 8 4\nSliceThickness: 1 1 1.5\n"
                     "Format: {}\nByteOrder: BigEndian\nObjectModel: I\nGridType: EQUIDISTANT\n", format));
  }
  seed("dat", "dat_offset.dat", "ObjectFileName: data.raw\nResolution: 8 8 8 2\nFormat: CHAR\nByteOffset: 16\n");
}

// Each real volume: its header pointed at the fixture data, and its centre
// block written by every writer in every encoding.
void real_volume_seeds(const fs::path& data) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(data)) {
    if (entry.is_regular_file() && is_header(entry.path().filename().string())) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& p : files) {
    const std::string stem = p.stem().string();
    if (p.extension() == ".nhdr") {
      // The real header, with the sizes made small and the data file one of the fixture's.
      std::string text = file_text(p);
      const bool gz = text.find("encoding: gzip") != std::string::npos;
      text = std::regex_replace(text, std::regex("sizes: [0-9]+ [0-9]+ [0-9]+"), "sizes: 8 8 4");
      text = std::regex_replace(text, std::regex("data file: [^\n]*(\n[^\n]*)*"),
                                gz ? "data file: data.raw.gz\n" : "data file: data.raw\n");
      seed("nrrd", "header_" + stem + ".nhdr", text);
    }
    std::shared_ptr<Volume> volume;
    try {
      volume = read_volume(p);
    } catch (const std::exception& e) {
      std::cerr << "fuzz_make_seeds: skipping " << p << ": " << e.what() << "\n";
      continue;
    }
    const auto small = crop(*volume);
    const std::string base = stem.substr(0, stem.find('.'));
    seed("nrrd", base + "_raw.nrrd", written([&](auto& f) { write_nrrd(f, *small); }, ".nrrd"));
    seed("nrrd", base + "_gzip_be.nrrd", written([&](auto& f) { write_nrrd(f, *small, true, std::endian::big); }, ".nrrd"));
    seed("metaimage", base + "_raw.mha", written([&](auto& f) { write_metaimage(f, *small); }, ".mha"));
    seed("metaimage", base + "_zlib_be.mha",
         written([&](auto& f) { write_metaimage(f, *small, true, std::endian::big); }, ".mha"));
    const std::pair<const char*, VtiWriteOptions> vti[] = {
        {"ascii", {VtiFormat::Ascii}},
        {"binary", {VtiFormat::Binary, false, false}},
        {"binary_zlib", {VtiFormat::Binary, true, true, std::endian::big}},
        {"appended_raw", {VtiFormat::AppendedRaw, false}},
        {"appended_zlib", {VtiFormat::AppendedRaw, true, false}},
        {"appended_base64", {VtiFormat::AppendedBase64, true}},
    };
    for (const auto& format : vti) {  // not a structured binding: clang 14 cannot capture one
      seed("vti", fmt::format("{}_{}.vti", base, format.first),
           written([&](auto& f) { write_vti(f, *small, format.second); }, ".vti"));
    }
    if (p.filename().string().ends_with(".nii.gz")) {
      // The real NIfTI header with dims 8x8x6 and the block's voxels after it.
      const std::string file = file_text(p);
      InflateStream in(std::as_bytes(std::span(file.data(), file.size())), p.string());
      std::vector<std::byte> header(352);
      in.read_exact(header, "header");
      const std::int16_t dims[] = {3, std::int16_t(small->dims().x), std::int16_t(small->dims().y),
                                   std::int16_t(small->dims().z), 1, 1, 1, 1};
      std::memcpy(header.data() + 40, dims, sizeof dims);
      std::vector<std::byte> nii = header;
      nii.insert(nii.end(), small->frame_data(0), small->frame_data(0) + small->frame_bytes());
      seed("nifti", base + ".nii", bytes_text(nii));
      seed("nifti", base + ".nii.gz", bytes_text(deflate_bytes(nii, CompressionFormat::Gzip)));
    }
  }
}

std::string obj_text(const TriangleMesh& m, int style) {
  std::string out = "# penumbra fuzz seed\nmtllib none.mtl\no mesh\n";
  for (const vec3& p : m.positions) out += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
  out += "vt 0 0\nvn 0 0 1\ns 1\n";
  const int n = int(m.positions.size());
  for (const auto& t : m.triangles) {
    if (style == 0) out += fmt::format("f {} {} {}\n", t.x + 1, t.y + 1, t.z + 1);
    if (style == 1) out += fmt::format("f {}/1/1 {}/1/1 {}/1/1\n", t.x + 1, t.y + 1, t.z + 1);
    if (style == 2) out += fmt::format("f {}//1 {}//1 \\\n {}//1\n", int(t.x) - n, int(t.y) - n, int(t.z) - n);
  }
  return out;
}

std::string ply_text(const TriangleMesh& m, const char* format) {
  const bool ascii = std::strcmp(format, "ascii") == 0;
  const bool big = std::strcmp(format, "binary_big_endian") == 0;
  std::string out = fmt::format(
      "ply\nformat {} 1.0\ncomment penumbra fuzz seed\nelement vertex {}\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face {}\nproperty list uchar int vertex_indices\n"
      "element extra 1\nproperty list uchar float values\nend_header\n",
      format, m.positions.size(), m.triangles.size());
  auto put = [&](auto value) {
    char b[sizeof value];
    std::memcpy(b, &value, sizeof value);
    if (big) std::reverse(b, b + sizeof value);
    out.append(b, sizeof value);
  };
  for (const vec3& p : m.positions) {
    if (ascii) {
      out += fmt::format("{} {} {} 200\n", p.x, p.y, p.z);
    } else {
      put(p.x), put(p.y), put(p.z), put(std::uint8_t(200));
    }
  }
  for (const auto& t : m.triangles) {
    if (ascii) {
      out += fmt::format("3 {} {} {}\n", t.x, t.y, t.z);
    } else {
      put(std::uint8_t(3)), put(std::int32_t(t.x)), put(std::int32_t(t.y)), put(std::int32_t(t.z));
    }
  }
  if (ascii) {
    out += "2 0.5 1.5\n";
  } else {
    put(std::uint8_t(2)), put(0.5f), put(1.5f);
  }
  return out;
}

void mesh_seeds() {
  for (const auto& [name, doc] : builtin_meshes()) {
    const auto mesh = make_builtin_mesh(name, 4);
    if (!mesh || mesh->triangles.size() > 400) continue;
    for (int style = 0; style < 3; ++style) seed("obj", fmt::format("{}_{}.obj", name, style), obj_text(*mesh, style));
    for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
      seed("ply", fmt::format("{}_{}.ply", name, format), ply_text(*mesh, format));
    }
  }
}

void preset_seeds() {
  seed("preset", "cool_to_warm.json",
       R"([{"ColorSpace": "Diverging", "Name": "Cool to Warm", "NanColor": [1, 1, 0],
  "RGBPoints": [0, 0.23, 0.299, 0.754, 0.5, 0.865, 0.865, 0.865, 1, 0.706, 0.016, 0.15]},
 {"Name": "Ramp", "RGBPoints": [-10, 0, 0, 0, 10, 1, 1, 1], "Points": [-10, 0, 0.5, 0, 0, 0.2, 0.25, 0, 10, 1, 0.5, 0]}])");
  seed("preset", "one_object.json", R"({"Name": "Grey", "RGBPoints": [0, 0, 0, 0, 255, 1, 1, 1]})");
  seed("preset", "xml_colormap.xml",
       "<ColorMaps>\n<ColorMap name=\"Blue\" space=\"RGB\">\n<Point x=\"0\" o=\"0\" r=\"0\" g=\"0\" b=\"1\"/>\n"
       "<Point x=\"1\" o=\"1\" r=\"1\" g=\"1\" b=\"1\"/>\n</ColorMap>\n</ColorMaps>\n");
}

// The scene with its files pointed at the fixture's and its volume small.
json fixture_scene(json scene) {
  if (scene.contains("volume")) {
    json& v = scene["volume"];
    if (v.contains("file")) v["file"] = "volume.nrrd";
    if (v.contains("size")) v["size"] = json::array({16, 16, 16});
  }
  if (scene.contains("meshes")) {
    for (json& m : scene["meshes"]) {
      if (m.contains("file")) m["file"] = "mesh.obj";
      if (m.contains("resolution")) m["resolution"] = 4;
      if (m.contains("material") && m["material"].contains("detail") && m["material"]["detail"].contains("texture")) {
        m["material"]["detail"]["texture"] = "volume.nrrd";
      }
    }
  }
  if (scene.contains("transfer_function") && scene["transfer_function"].contains("preset")) {
    scene["transfer_function"]["preset"]["file"] = "preset.json";
  }
  return scene;
}

void scene_seeds(const fs::path& scenes) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(scenes)) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& p : files) {
    json scene;
    try {
      scene = json::parse(file_text(p));
    } catch (const json::exception&) {
      continue;
    }
    if (!scene.is_object() || !scene.contains("volume")) continue;  // reference metadata, not scenes
    const std::string text = fixture_scene(scene).dump(1);
    const std::string name = p.parent_path().filename().string() + "_" + p.filename().string();
    seed("scene", name, text);
    seed("server", "put_" + name, "\x00" + text);
    seed("server", "frame_" + name,
         "\x01" + json{{"scene", fixture_scene(scene)}, {"width", 12}, {"height", 8}, {"preview", true}}.dump());
  }
  // What no repository scene has: a mesh file with a volume texture, a preset file.
  const std::string files_scene = R"({"volume": {"file": "volume.nrrd", "spacing": [1, 1, 2], "time_step": 0},
 "transfer_function": {"preset": {"file": "preset.json", "name": "Grey"}, "range": "data", "density_scale": 2},
 "meshes": [{"file": "mesh.obj", "scale": 4, "material": {"detail": {"type": "texture", "texture": "volume.nrrd"}}}],
 "lights": [{"type": "point", "position": [20, 0, 0]}], "render": {"technique": "convolution"}})";
  seed("scene", "fixture_files.json", files_scene);
  seed("server", "put_fixture_files.json", "\x00" + files_scene);
  seed("server", "frame_camera.json",
       std::string("\x01") + R"({"camera": {"eye": [0, -200, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov_deg": 40},
 "width": 16, "height": 16, "format": "png", "step_scale": 4, "quality": 50})");
  seed("server", "query_frame.txt", "\x02width=16&height=9&format=jpeg&quality=90&preview=1");
  seed("server", "query_png.txt", "\x02width=3&height=2&format=png");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: fuzz_make_seeds OUT SHARED_DATA SCENES\n";
    return 2;
  }
  g_out = argv[1];
  set_memory_budget_bytes(std::uint64_t(1) << 30);
  detached_seeds();
  real_volume_seeds(argv[2]);
  mesh_seeds();
  preset_seeds();
  scene_seeds(argv[3]);
  std::cout << "fuzz_make_seeds: " << g_count << " seeds in " << g_out.string() << "\n";
  return 0;
}
