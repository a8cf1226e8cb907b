#include "server/data_directory.h"

#include "server/http_error.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

#include <fstream>

namespace penumbra::server {
namespace {

namespace fs = std::filesystem;
using testing::test_data_dir;
using testing::test_data_root;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  ASSERT_TRUE(fs::exists(path)) << path;
}

// Mesh files beside the shared test volumes (made once per process):
//   data/tet.obj, data/sub/tet.ply, data/UPPER.OBJ   meshes inside the folder
//   data/escape.obj      symlink to ../outside/secret.obj (leaves: refused)
//   data/text_link.obj   symlink to notes.txt (inside, but not a mesh)
//   data/shape.stl       not a supported mesh format
//   outside/secret.obj   a mesh outside the data folder
void make_mesh_files() {
  static const bool made = [] {
    const std::string tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const fs::path data = test_data_dir();
    write_text(data / "tet.obj", tet);
    write_text(data / "UPPER.OBJ", tet);
    write_text(data / "shape.stl", "solid nothing\nendsolid nothing\n");
    write_text(data / "sub" / "tet.ply",
               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    write_text(test_data_root() / "outside" / "secret.obj", tet);
    fs::create_symlink("../outside/secret.obj", data / "escape.obj");
    fs::create_symlink("notes.txt", data / "text_link.obj");
    return true;
  }();
  (void)made;
}

int status_of_mesh(const DataDirectory& data, std::string_view path) {
  try {
    data.resolve_mesh(path, "meshes[0].file");
  } catch (const HttpError& e) {
    EXPECT_EQ(e.key(), "meshes[0].file") << path;
    EXPECT_NE(std::string(e.what()), "") << path;
    return e.status();
  }
  return 200;
}

int status_of_resolve(const DataDirectory& data, std::string_view path) {
  try {
    data.resolve_volume(path, "volume.file");
  } catch (const HttpError& e) {
    EXPECT_EQ(e.key(), "volume.file");
    return e.status();
  }
  return 200;
}

TEST(DataDirectory, ResolvesFilesInsideTheFolder) {
  const DataDirectory data(test_data_dir());
  EXPECT_EQ(data.resolve_volume("tiny.nrrd", "k"), std::filesystem::canonical(test_data_dir() / "tiny.nrrd"));
  EXPECT_EQ(data.resolve_volume("sub/nested.nrrd", "k").filename(), "nested.nrrd");
  EXPECT_EQ(data.resolve_volume("./tiny.nrrd", "k").filename(), "tiny.nrrd");
  // A symlink whose target stays inside is fine: it resolves to the target.
  EXPECT_EQ(data.resolve_volume("inside_link.nrrd", "k").filename(), "tiny.nrrd");
}

TEST(DataDirectory, RefusesEveryWayOut) {
  const DataDirectory data(test_data_dir());
  EXPECT_EQ(status_of_resolve(data, "../outside/secret.nrrd"), 400);      // ".."
  EXPECT_EQ(status_of_resolve(data, "sub/../tiny.nrrd"), 400);            // ".." even when it would stay inside
  EXPECT_EQ(status_of_resolve(data, "sub/../../outside/secret.nrrd"), 400);
  EXPECT_EQ(status_of_resolve(data, (test_data_dir() / "tiny.nrrd").string()), 400);  // absolute
  EXPECT_EQ(status_of_resolve(data, "/etc/passwd"), 400);
  EXPECT_EQ(status_of_resolve(data, "escape.nrrd"), 403);                 // symlink to a file outside
  EXPECT_EQ(status_of_resolve(data, "linkdir/secret.nrrd"), 403);         // through a symlinked folder
  EXPECT_EQ(status_of_resolve(data, "tiny.nrrd\\..\\x"), 400);            // backslashes
  EXPECT_EQ(status_of_resolve(data, std::string_view("tiny\0.nrrd", 10)), 400);
  EXPECT_EQ(status_of_resolve(data, ""), 400);
  EXPECT_EQ(status_of_resolve(data, "missing.nrrd"), 404);
  EXPECT_EQ(status_of_resolve(data, "notes.txt"), 415);                   // not a volume format
  EXPECT_EQ(status_of_resolve(data, "sub"), 400);                         // a folder
}

TEST(DataDirectory, ListsOnlyVolumesThatStayInside) {
  const DataDirectory data(test_data_dir());
  std::vector<std::string> paths;
  for (const DataEntry& e : data.list_volumes()) {
    paths.push_back(e.path);
    EXPECT_GT(e.bytes, 0u) << e.path;
  }
  EXPECT_EQ(paths, (std::vector<std::string>{"inside_link.nrrd", "series.nrrd", "sub/nested.nrrd", "tiny.nrrd"}));
}

TEST(DataDirectory, WithoutAFolderNothingResolves) {
  const DataDirectory none{std::filesystem::path()};
  EXPECT_FALSE(none.available());
  EXPECT_TRUE(none.list_volumes().empty());
  EXPECT_EQ(status_of_resolve(none, "tiny.nrrd"), 404);
  const DataDirectory missing(test_data_dir() / "no-such-folder");
  EXPECT_FALSE(missing.available());
}

TEST(DataDirectory, ResolvesMeshFilesInsideTheFolder) {
  make_mesh_files();
  const DataDirectory data(test_data_dir());
  EXPECT_EQ(data.resolve_mesh("tet.obj", "k"), fs::canonical(test_data_dir() / "tet.obj"));
  EXPECT_EQ(data.resolve_mesh("sub/tet.ply", "k"), fs::canonical(test_data_dir() / "sub" / "tet.ply"));
  EXPECT_EQ(data.resolve_mesh("./tet.obj", "k").filename(), "tet.obj");
  EXPECT_EQ(data.resolve_mesh("UPPER.OBJ", "k").filename(), "UPPER.OBJ");  // extensions in any case
  EXPECT_EQ(status_of_mesh(data, "tet.obj"), 200);
}

TEST(DataDirectory, RefusesMeshesOutsideTheFolderOrOfTheWrongKind) {
  make_mesh_files();
  const DataDirectory data(test_data_dir());
  EXPECT_EQ(status_of_mesh(data, "../outside/secret.obj"), 400);              // ".."
  EXPECT_EQ(status_of_mesh(data, "sub/../tet.obj"), 400);
  EXPECT_EQ(status_of_mesh(data, (test_data_dir() / "tet.obj").string()), 400);  // absolute, even inside
  EXPECT_EQ(status_of_mesh(data, (test_data_root() / "outside" / "secret.obj").string()), 400);
  EXPECT_EQ(status_of_mesh(data, "escape.obj"), 403);                        // symlink to a file outside
  EXPECT_EQ(status_of_mesh(data, "linkdir/secret.obj"), 403);                // through a symlinked folder
  EXPECT_EQ(status_of_mesh(data, "missing.obj"), 404);
  EXPECT_EQ(status_of_mesh(data, "sub/missing.ply"), 404);
  EXPECT_EQ(status_of_mesh(data, "shape.stl"), 415);                         // not a mesh format
  EXPECT_EQ(status_of_mesh(data, "notes.txt"), 415);
  EXPECT_EQ(status_of_mesh(data, "tiny.nrrd"), 415);                         // a volume is not a mesh
  EXPECT_EQ(status_of_mesh(data, "text_link.obj"), 415);                     // named .obj, but is a text file
  EXPECT_EQ(status_of_mesh(data, ""), 400);
  EXPECT_EQ(status_of_mesh(data, "sub"), 400);                               // a folder
  // And the other way round: a mesh is not a volume.
  EXPECT_EQ(status_of_resolve(data, "tet.obj"), 415);
  const DataDirectory none{fs::path()};
  EXPECT_EQ(status_of_mesh(none, "tet.obj"), 404);
}

TEST(DataDirectory, RecognisesVolumeExtensionsCaseInsensitively) {
  EXPECT_TRUE(DataDirectory::is_volume_file_name("a.NHDR"));
  EXPECT_TRUE(DataDirectory::is_volume_file_name("head.nii.gz"));
  EXPECT_FALSE(DataDirectory::is_volume_file_name("a.raw"));
  EXPECT_FALSE(DataDirectory::is_volume_file_name(".nrrd"));
  EXPECT_FALSE(DataDirectory::is_volume_file_name("notes.txt"));
}

}  // namespace
}  // namespace penumbra::server
