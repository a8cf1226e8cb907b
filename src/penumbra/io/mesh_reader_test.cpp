#include "penumbra/io/mesh_reader.h"

#include "penumbra/io/io_test_support.h"

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

namespace penumbra {
namespace {

using test::TempDir;

// A box with corners chosen to be exact in float, corner i = (bit 0, bit 1,
// bit 2) of i, and its six faces as quads counter-clockwise from outside.
vec3 corner(int i) {
  return vec3((i & 1) ? 1.5f : -0.5f, (i & 2) ? 2.25f : -1.0f, (i & 4) ? 0.125f : -3.0f);
}
constexpr std::array<std::array<std::uint32_t, 4>, 6> kQuads = {{
    {0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};

// The quads as fans: (a, b, c), (a, c, d).
std::vector<glm::uvec3> expected_triangles() {
  std::vector<glm::uvec3> triangles;
  for (const auto& q : kQuads) {
    triangles.emplace_back(q[0], q[1], q[2]);
    triangles.emplace_back(q[0], q[2], q[3]);
  }
  return triangles;
}

void expect_box(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.positions.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(mesh.positions[i], corner(i)) << "vertex " << i;
  EXPECT_EQ(mesh.triangles, expected_triangles());
  // Outward winding gives the box's positive volume 2 * 3.25 * 3.125.
  double volume = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    volume += glm::dot(dvec3(mesh.positions[t[0]]),
                       glm::cross(dvec3(mesh.positions[t[1]]), dvec3(mesh.positions[t[2]]))) / 6.0;
  }
  EXPECT_NEAR(volume, 2.0 * 3.25 * 3.125, 1e-9);
  EXPECT_NO_THROW(mesh.validate("mesh"));
}

// Expects an IoError whose message names the file and contains `fragment`.
void expect_mesh_error(const std::filesystem::path& path, std::string_view fragment) {
  test::expect_io_error([&] { read_mesh(path); }, path.filename().string());
  test::expect_io_error([&] { read_mesh(path); }, fragment);
}

TEST(MeshReader, ReadsObjWithSlashesNegativeIndicesAndIgnoredStatements) {
  TempDir dir;
  std::ostringstream obj;
  obj << "# a box\r\nmtllib box.mtl\no box\n\n";
  for (int i = 0; i < 8; ++i) {
    const vec3 p = corner(i);
    obj << "v " << p.x << ' ' << p.y << ' ' << p.z << (i == 3 ? " 1.0" : "") << (i == 5 ? " 0.5 0.5 0.5" : "")
        << "\r\n";
  }
  obj << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 -1\nvp 0.5\ng side\nusemtl red\ns off\ncstype bezier\n";
  obj << "f 1/1/1 3/2/1 4/3/1 2/4/1\n";   // i/t/n
  obj << "f 5//1 6//1 8//1 7//1 # top\n";  // i//n and a trailing comment
  obj << "f -8 -7 -3 -4\n";                // relative: 8 vertices so far
  obj << "f 3/1 7/2 \\\n 8/3 4/4\n";       // i/t, continued on the next line
  obj << "f\t1 5 7 3\n";
  obj << "f 2/1/1 -5/2/1 8 6//1\n";        // mixed forms
  test::write_file(dir / "box.obj", obj.str());
  expect_box(read_mesh(dir / "box.obj"));
  // The extension is case-insensitive.
  std::filesystem::copy_file(dir / "box.obj", dir / "BOX.OBJ");
  expect_box(read_mesh(dir / "BOX.OBJ"));
}

TEST(MeshReader, FansObjPolygonsAndAcceptsFacesBeforeTheirVertices) {
  TempDir dir;
  test::write_file(dir / "pentagon.obj", "f 1 2 3 4 5\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 2 0\nv 0 1 0\n");
  const TriangleMesh mesh = read_mesh(dir / "pentagon.obj");
  EXPECT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.triangles,
            (std::vector<glm::uvec3>{glm::uvec3(0, 1, 2), glm::uvec3(0, 2, 3), glm::uvec3(0, 3, 4)}));
}

TEST(MeshReader, RejectsMalformedObj) {
  TempDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n", "line 2: vertex value 'x' is not a number"},
      {"v 0 0\n", "line 1: a vertex needs 3 coordinates"},
      {"v 0 0 nan\n", "line 1: vertex position is not finite"},
      {"v 0 1e300 0\n", "line 1: vertex position is not finite (or beyond the float range)"},  // was UB as a float
      {vertices + "f 1 2\n", "line 4: a face needs at least 3 vertices"},
      {vertices + "f 1 2 0\n", "line 4: vertex index 0"},
      {vertices + "\nf 1 2 3\nf 1 2 4\n", "line 6: vertex index 4 is out of range"},
      {vertices + "f -1 -2 -4\n", "line 4: relative vertex index -4"},
      {vertices + "f 1/1/1/1 2 3\n", "has more than 3 parts"},
      {vertices + "f 1/x 2 3\n", "face corner '1/x' is malformed"},
      {vertices + "f /1 2 3\n", "face corner '/1' has no vertex index"},
      {vertices + "f 1.5 2 3\n", "face corner '1.5' has no vertex index"},
      {vertices, "OBJ file has no faces"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].first);
    const auto path = dir / ("bad" + std::to_string(i) + ".obj");
    test::write_file(path, cases[i].first);
    expect_mesh_error(path, cases[i].second);
  }
  expect_mesh_error(dir / "missing.obj", "file not found");
  test::write_file(dir / "box.stl", vertices);
  expect_mesh_error(dir / "box.stl", "unknown mesh format '.stl'");
}

// A PLY file built value by value, written as ascii or binary.
enum class T { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyBuilder {
  std::string header;
  std::vector<std::vector<std::pair<T, double>>> rows;  // one per element instance

  std::vector<std::byte> file(const std::string& format) const {
    std::string text = "ply\nformat " + format + " 1.0\n" + header + "end_header\n";
    const auto header_bytes = test::text_bytes(text);
    std::vector<std::byte> bytes(header_bytes.begin(), header_bytes.end());
    for (const auto& row : rows) {
      std::ostringstream line;
      line.precision(17);
      for (const auto& [type, value] : row) {
        if (format == "ascii") {
          if (type == T::Float32 || type == T::Float64) {
            line << value << ' ';
          } else {
            line << static_cast<long long>(value) << ' ';
          }
          continue;
        }
        const std::endian order = format == "binary_big_endian" ? std::endian::big : std::endian::little;
        append(bytes, type, value, order);
      }
      if (format == "ascii") {
        const std::string s = line.str() + "\n";
        const auto line_bytes = test::text_bytes(s);
        bytes.insert(bytes.end(), line_bytes.begin(), line_bytes.end());
      }
    }
    return bytes;
  }

  static void append(std::vector<std::byte>& bytes, T type, double value, std::endian order) {
    std::array<std::byte, 8> raw{};
    std::size_t size = 0;
    const auto put = [&](auto typed) {
      size = sizeof(typed);
      std::memcpy(raw.data(), &typed, size);
    };
    switch (type) {
      case T::Int8: put(static_cast<std::int8_t>(value)); break;
      case T::UInt8: put(static_cast<std::uint8_t>(value)); break;
      case T::Int16: put(static_cast<std::int16_t>(value)); break;
      case T::UInt16: put(static_cast<std::uint16_t>(value)); break;
      case T::Int32: put(static_cast<std::int32_t>(value)); break;
      case T::UInt32: put(static_cast<std::uint32_t>(value)); break;
      case T::Float32: put(static_cast<float>(value)); break;
      case T::Float64: put(value); break;
    }
    convert_byte_order(std::span(raw.data(), size), size, order);
    bytes.insert(bytes.end(), raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(size));
  }
};

// The box with properties around x, y, z, an element before and one after
// the faces, and a list property before the face indices.
PlyBuilder box_ply(const std::string& count_type, T count, const std::string& index_type, T index) {
  PlyBuilder ply;
  ply.header =
      "comment written by mesh_reader_test\nobj_info nothing\n"
      "element vertex 8\nproperty float32 x\nproperty float y\nproperty uchar red\nproperty double z\n"
      "property short nz\n"
      "element edge 2\nproperty int vertex1\nproperty list uint8 uint16 path\nproperty int vertex2\n"
      "element face 6\nproperty list uchar float texcoord\nproperty list " +
      count_type + " " + index_type +
      " vertex_indices\nproperty uchar flags\n"
      "element material 1\nproperty list int char name\n";
  for (int i = 0; i < 8; ++i) {
    const vec3 p = corner(i);
    ply.rows.push_back({{T::Float32, p.x}, {T::Float32, p.y}, {T::UInt8, 200}, {T::Float64, p.z}, {T::Int16, -7}});
  }
  ply.rows.push_back({{T::Int32, 0}, {T::UInt8, 2}, {T::UInt16, 5}, {T::UInt16, 6}, {T::Int32, 1}});
  ply.rows.push_back({{T::Int32, 2}, {T::UInt8, 0}, {T::Int32, 3}});
  for (const auto& q : kQuads) {
    ply.rows.push_back({{T::UInt8, 2}, {T::Float32, 0.25}, {T::Float32, 0.75}, {count, 4}, {index, q[0]},
                        {index, q[1]}, {index, q[2]}, {index, q[3]}, {T::UInt8, 9}});
  }
  ply.rows.push_back({{T::Int32, 3}, {T::Int8, 'b'}, {T::Int8, 'o'}, {T::Int8, 'x'}});
  return ply;
}

TEST(MeshReader, ReadsPlyAsciiAndBinaryInBothByteOrders) {
  TempDir dir;
  test::write_file(dir / "ascii.ply", box_ply("uchar", T::UInt8, "int", T::Int32).file("ascii"));
  test::write_file(dir / "le.ply", box_ply("ushort", T::UInt16, "uint", T::UInt32).file("binary_little_endian"));
  test::write_file(dir / "be.ply", box_ply("uint", T::UInt32, "int32", T::Int32).file("binary_big_endian"));
  test::write_file(dir / "be8.PLY", box_ply("uint8", T::UInt8, "ushort", T::UInt16).file("binary_big_endian"));
  for (const char* name : {"ascii.ply", "le.ply", "be.ply", "be8.PLY"}) {
    SCOPED_TRACE(name);
    expect_box(read_mesh(dir / name));
  }
}

TEST(MeshReader, ReadsPlyVertexIndexNameAndFansPolygons) {
  TempDir dir;
  PlyBuilder ply;
  ply.header = "element vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
               "element face 1\nproperty list uchar int vertex_index\n";
  for (int i = 0; i < 5; ++i) ply.rows.push_back({{T::Float64, i}, {T::Float64, i * i}, {T::Float64, 0}});
  ply.rows.push_back({{T::UInt8, 5}, {T::Int32, 4}, {T::Int32, 3}, {T::Int32, 2}, {T::Int32, 1}, {T::Int32, 0}});
  for (const char* format : {"ascii", "binary_little_endian"}) {
    SCOPED_TRACE(format);
    test::write_file(dir / "fan.ply", ply.file(format));
    const TriangleMesh mesh = read_mesh(dir / "fan.ply");
    EXPECT_EQ(mesh.positions.size(), 5u);
    EXPECT_EQ(mesh.positions[3], vec3(3, 9, 0));
    EXPECT_EQ(mesh.triangles,
              (std::vector<glm::uvec3>{glm::uvec3(4, 3, 2), glm::uvec3(4, 2, 1), glm::uvec3(4, 1, 0)}));
  }
}

TEST(MeshReader, RejectsHugePlyCountsBeforeAllocating) {
  TempDir dir;
  // 10^12 vertices of 12 bytes would be 12 TB; the file has a few hundred bytes.
  for (const char* format : {"ascii", "binary_little_endian"}) {
    SCOPED_TRACE(format);
    PlyBuilder ply;
    ply.header = "element vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face 1\nproperty list uchar int vertex_indices\n";
    ply.rows.push_back({{T::Float32, 0}, {T::Float32, 0}, {T::Float32, 0}});
    test::write_file(dir / "huge.ply", ply.file(format));
    expect_mesh_error(dir / "huge.ply", "declares 1000000000000 'vertex' elements");
    // A face count that overflows 64 bits when multiplied by its size.
    ply.header = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face 9223372036854775807\nproperty list uint int vertex_indices\n";
    for (int i = 0; i < 2; ++i) ply.rows.push_back({{T::Float32, 0}, {T::Float32, 0}, {T::Float32, 0}});
    test::write_file(dir / "huge.ply", ply.file(format));
    expect_mesh_error(dir / "huge.ply", "'face' elements");
  }
}

TEST(MeshReader, RejectsMalformedPly) {
  TempDir dir;
  const std::string xyz = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"plx\nformat ascii 1.0\nend_header\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\n" + xyz, "no 'end_header'"},
      {"ply\nformat utf8 1.0\nend_header\n", "header line 2: unknown format 'utf8'"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "header line 3: 'property' before any 'element'"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float16 x\nend_header\n", "unknown type 'float16'"},
      {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", "element count '-3'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
       "list count type 'float' is not an integer type"},
      {"ply\nformat ascii 1.0\nfrobnicate\nend_header\n", "unknown keyword 'frobnicate'"},
      {"ply\nformat ascii 1.0\n" + xyz + "end_header\n" + body, "no 'face' element"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
       "no scalar 'z' property"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty list uchar int corners\nend_header\n" + body +
           "3 0 1 2\n",
       "no 'vertex_indices' list property"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty list uchar float vertex_indices\nend_header\n" +
           body + "3 0 1 2\n",
       "not of an integer type"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           body + "3 0 1 3\n",
       "element 'face' 0, property 'vertex_indices': vertex index 3 is out of range"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 2\nproperty list uchar int vertex_indices\nend_header\n" +
           body + "3 0 1 2\n2 0 1\n",
       "element 'face' 1, property 'vertex_indices': a face needs at least 3 vertices"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
       "element 'vertex' 1, property 'y': 'zero' is not a number"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           body + "3 0 1.5 2\n",
       "'1.5' is not an integer"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           body + "4 0 1 2\n",
       "element 'face' 0, property 'vertex_indices': the file ends inside it"},
      {"ply\nformat ascii 1.0\n" + xyz + "element face 0\nproperty list uchar int vertex_indices\nend_header\n" +
           body,
       "PLY file has no faces"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].first);
    const auto path = dir / ("bad" + std::to_string(i) + ".ply");
    test::write_file(path, cases[i].first);
    expect_mesh_error(path, cases[i].second);
  }

  // Binary: a face list longer than the bytes that are left.
  PlyBuilder ply;
  ply.header = xyz + "element face 1\nproperty list uchar int vertex_indices\n";
  for (int i = 0; i < 3; ++i) ply.rows.push_back({{T::Float32, i}, {T::Float32, 0}, {T::Float32, 0}});
  ply.rows.push_back({{T::UInt8, 200}, {T::Int32, 0}, {T::Int32, 1}, {T::Int32, 2}});
  test::write_file(dir / "short.ply", ply.file("binary_little_endian"));
  expect_mesh_error(dir / "short.ply", "element 'face' 0, property 'vertex_indices': the file ends inside it");
  // A vertex count that the body cannot hold: 5 x 12 bytes, 49 follow.
  ply.header = "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\n";
  ply.rows.back() = {{T::UInt8, 3}, {T::Int32, 0}, {T::Int32, 1}, {T::Int32, 2}};
  test::write_file(dir / "short.ply", ply.file("binary_big_endian"));
  expect_mesh_error(dir / "short.ply", "declares 5 'vertex' elements");
}

}  // namespace
}  // namespace penumbra
