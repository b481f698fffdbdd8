#include "server/model_store.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/escaping.h"

#include "common/hash/sha256.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

const char kTetrahedronObj[] =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

pb::UploadModelChunk Header(const std::string& name, const std::string& data) {
  pb::UploadModelChunk chunk;
  chunk.mutable_header()->set_name(name);
  chunk.mutable_header()->set_format("obj");
  chunk.mutable_header()->set_size_bytes(static_cast<int64_t>(data.size()));
  chunk.mutable_header()->set_sha256(Sha256Of(data));
  return chunk;
}

pb::UploadModelChunk Data(const std::string& data) {
  pb::UploadModelChunk chunk;
  chunk.set_data(data);
  return chunk;
}

std::string TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("model_store_test_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

// Chunks assemble into the file; it is kept under "<name>.<format>"; the
// same bytes again return it, other bytes under its id are ALREADY_EXISTS,
// also after a restart over the same folder; Delete removes it.
TEST(ModelStoreTest, AssemblesVerifiesAndKeeps) {
  const std::string data = kTetrahedronObj;
  ModelUpload upload(1 << 20);
  ASSERT_TRUE(upload.Add(Header("tet", data)).ok());
  ASSERT_TRUE(upload.Add(Data(data.substr(0, 10))).ok());
  ASSERT_TRUE(upload.Add(Data(data.substr(10))).ok());
  ModelStore store(TempDir("keeps"), 4);
  ASSERT_TRUE(store.Load().ok());
  absl::StatusOr<StoredModel> stored = store.Store(upload);
  ASSERT_TRUE(stored.ok()) << stored.status();
  EXPECT_EQ(stored->model_id, "tet.obj");
  EXPECT_EQ(stored->triangles, 4);
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(store.dir()) / "tet.obj"));
  absl::StatusOr<StoredModel> again = store.Store(upload);
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_TRUE(again->existed);
  EXPECT_EQ(again->triangles, 4);
  const std::string other = std::string(kTetrahedronObj) + "f 1 2 3\n";
  ModelUpload changed(1 << 20);
  ASSERT_TRUE(changed.Add(Header("tet", other)).ok());
  ASSERT_TRUE(changed.Add(Data(other)).ok());
  EXPECT_EQ(store.Store(changed).status().code(), absl::StatusCode::kAlreadyExists);
  // A store over the same folder (a restart) knows the model by its bytes.
  ModelStore reopened(store.dir(), 4);
  ASSERT_TRUE(reopened.Load().ok());
  EXPECT_TRUE(reopened.Has("tet.obj"));
  EXPECT_EQ(reopened.Store(changed).status().code(), absl::StatusCode::kAlreadyExists);
  EXPECT_TRUE(reopened.Store(upload).ok());
  EXPECT_TRUE(reopened.Delete("tet.obj").ok());
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(store.dir()) / "tet.obj"));
  EXPECT_EQ(reopened.Delete("tet.obj").code(), absl::StatusCode::kNotFound);
  std::filesystem::remove_all(store.dir());
}

// Out-of-order, oversized, short, corrupted and unreadable uploads are
// refused and leave nothing in the store.
TEST(ModelStoreTest, RefusesBadUploads) {
  const std::string data = kTetrahedronObj;
  EXPECT_EQ(ModelUpload(1 << 20).Add(Data(data)).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(ModelUpload(8).Add(Header("tet", data)).code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(ModelUpload(1 << 20).Add(Header("a/b", data)).code(),
            absl::StatusCode::kInvalidArgument);

  ModelUpload too_much(1 << 20);
  ASSERT_TRUE(too_much.Add(Header("tet", data)).ok());
  EXPECT_EQ(too_much.Add(Data(data + "x")).code(), absl::StatusCode::kInvalidArgument);

  ModelUpload short_upload(1 << 20);
  ASSERT_TRUE(short_upload.Add(Header("tet", data)).ok());
  ASSERT_TRUE(short_upload.Add(Data(data.substr(1))).ok());
  EXPECT_EQ(short_upload.Verify().code(), absl::StatusCode::kInvalidArgument);

  std::string corrupted = data;
  corrupted[0] = 'x';
  ModelUpload wrong_sum(1 << 20);
  pb::UploadModelChunk header = Header("tet", data);
  ASSERT_TRUE(wrong_sum.Add(header).ok());
  ASSERT_TRUE(wrong_sum.Add(Data(corrupted)).ok());
  EXPECT_EQ(wrong_sum.Verify().code(), absl::StatusCode::kInvalidArgument);

  const std::string garbage = "solid nothing\nendsolid\n";
  ModelUpload unreadable(1 << 20);
  ASSERT_TRUE(unreadable.Add(Header("empty", garbage)).ok());
  ASSERT_TRUE(unreadable.Add(Data(garbage)).ok());
  ModelStore store(TempDir("refuses"), 4);
  EXPECT_EQ(store.Store(unreadable).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(!std::filesystem::exists(store.dir()) || std::filesystem::is_empty(store.dir()));
  std::filesystem::remove_all(store.dir());
}

// An upload that crashes its reader (Inventor nested past any stack) is
// refused with the crash named, the store goes on serving, and nothing of
// the upload is left in its folder.
TEST(ModelStoreTest, UploadThatCrashesTheReaderIsRefused) {
  std::string data = "#Inventor V2.1 ascii\n";
  for (int i = 0; i < 200000; ++i) data += "Separator {\n";
  data += std::string(200000, '}');
  ModelUpload upload(16 << 20);
  pb::UploadModelChunk header = Header("deep", data);
  header.mutable_header()->set_format("iv");
  ASSERT_TRUE(upload.Add(header).ok());
  ASSERT_TRUE(upload.Add(Data(data)).ok());
  ModelStore store(TempDir("crash"), 4);
  absl::StatusOr<StoredModel> stored = store.Store(upload);
  ASSERT_FALSE(stored.ok());
  EXPECT_EQ(stored.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(stored.status().message().find("model 'deep.iv' does not import"), std::string::npos)
      << stored.status();
  EXPECT_TRUE(std::filesystem::is_empty(store.dir()));

  const std::string tetrahedron = kTetrahedronObj;
  ModelUpload good(1 << 20);
  ASSERT_TRUE(good.Add(Header("tet", tetrahedron)).ok());
  ASSERT_TRUE(good.Add(Data(tetrahedron)).ok());
  EXPECT_TRUE(store.Store(good).ok());
  std::filesystem::remove_all(store.dir());
}

ModelUpload Upload(const std::string& name, const std::string& data) {
  ModelUpload upload(1 << 20);
  EXPECT_TRUE(upload.Add(Header(name, data)).ok());
  EXPECT_TRUE(upload.Add(Data(data)).ok());
  return upload;
}

std::vector<std::string> Names(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Content is kept once, in a file named by its SHA-256; each id is a link
// to it. Deleting one of two ids of the same bytes keeps the content;
// deleting the last removes it.
TEST(ModelStoreTest, ContentIsNamedBySha256AndShared) {
  const std::string data = kTetrahedronObj;
  const std::string content = absl::BytesToHexString(Sha256Of(data)) + ".obj";
  ModelStore store(TempDir("content"), 4);
  ASSERT_TRUE(store.Load().ok());
  ASSERT_TRUE(store.Store(Upload("a", data)).ok());
  ASSERT_TRUE(store.Store(Upload("b", data)).ok());
  EXPECT_EQ(Names(store.dir()), (std::vector<std::string>{"a.obj", "b.obj", content}));
  const std::filesystem::path dir = store.dir();
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "a.obj"));
  EXPECT_EQ(std::filesystem::read_symlink(dir / "a.obj").string(), content);
  ASSERT_TRUE(store.Delete("a.obj").ok());
  EXPECT_EQ(Names(store.dir()), (std::vector<std::string>{"b.obj", content}));
  ASSERT_TRUE(store.Delete("b.obj").ok());
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}

// Loading a folder: what a crash left of unacknowledged uploads goes (a
// hidden staged file, content no id points at); a model file named by its
// id (the earlier layout) moves to its content's name; a model whose
// content is missing or damaged stops the load, naming the file.
TEST(ModelStoreTest, LoadCleansMigratesAndRefusesDamage) {
  const std::string data = kTetrahedronObj;
  const std::string content = absl::BytesToHexString(Sha256Of(data)) + ".obj";
  const std::filesystem::path dir = TempDir("load");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / ".cut.obj") << "half";
  std::ofstream(dir / (std::string(64, 'a') + ".obj")) << "orphan";
  std::ofstream(dir / "old.obj") << data;
  {
    ModelStore store(dir.string(), 4);
    ASSERT_TRUE(store.Load().ok());
    EXPECT_TRUE(store.Has("old.obj"));
    EXPECT_EQ(Names(dir.string()), (std::vector<std::string>{content, "old.obj"}));
    EXPECT_TRUE(std::filesystem::is_symlink(dir / "old.obj"));
  }
  {
    std::ofstream(dir / content, std::ios::trunc) << data << "# changed\n";
    ModelStore store(dir.string(), 4);
    const absl::Status damaged = store.Load();
    EXPECT_EQ(damaged.code(), absl::StatusCode::kFailedPrecondition);
    EXPECT_NE(damaged.message().find(content), std::string::npos) << damaged;
  }
  {
    std::filesystem::remove(dir / content);
    ModelStore store(dir.string(), 4);
    const absl::Status missing = store.Load();
    EXPECT_EQ(missing.code(), absl::StatusCode::kFailedPrecondition);
    EXPECT_NE(missing.message().find("is missing"), std::string::npos) << missing;
    EXPECT_NE(missing.message().find("old.obj"), std::string::npos) << missing;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace hs
