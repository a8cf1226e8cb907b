#include "server/data_directory.h"

#include "server/http_error.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

namespace penumbra::server {
namespace {

using testing::test_data_dir;

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

TEST(DataDirectory, RecognisesVolumeExtensionsCaseInsensitively) {
  EXPECT_TRUE(DataDirectory::is_volume_file_name("a.NHDR"));
  EXPECT_TRUE(DataDirectory::is_volume_file_name("head.nii.gz"));
  EXPECT_FALSE(DataDirectory::is_volume_file_name("a.raw"));
  EXPECT_FALSE(DataDirectory::is_volume_file_name(".nrrd"));
  EXPECT_FALSE(DataDirectory::is_volume_file_name("notes.txt"));
}

}  // namespace
}  // namespace penumbra::server
