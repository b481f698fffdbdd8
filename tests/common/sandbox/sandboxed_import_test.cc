#include "common/sandbox/sandboxed_import.h"

#include <dirent.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/common/sanitized_build.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string Write(const std::string& name, const std::string& text) {
  const std::filesystem::path path = ScratchDir("sandbox-" + name) / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

int OpenDescriptors() {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
    (void)entry;
    ++count;
  }
  return count;
}

// A file imported in the worker is the same object, to the bit, as one
// imported in this process (files without references to other files).
TEST(SandboxedImportTest, SameModelAsInProcess) {
  for (const char* file : {"cube_binary.stl", "cube.ply", "cube.iv", "cube.wrl", "two_cubes.dae",
                           "kidney.obj", "l_prism.obj"}) {
    SCOPED_TRACE(file);
    ImportOptions options;
    options.unit_scale = 0.001;
    absl::StatusOr<ImportedModel> here = ImportModel(TestDataPath(file), options);
    absl::StatusOr<ImportedModel> there = SandboxedImport(TestDataPath(file), options);
    ASSERT_TRUE(here.ok()) << here.status();
    ASSERT_TRUE(there.ok()) << there.status();
    EXPECT_EQ(there->object.name(), here->object.name());
    EXPECT_EQ(there->reader, here->reader);
    ASSERT_EQ(there->object.num_vertices(), here->object.num_vertices());
    for (int v = 0; v < here->object.num_vertices(); ++v) {
      ASSERT_EQ(there->object.position(v), here->object.position(v)) << v;
    }
    ASSERT_EQ(there->object.num_faces(), here->object.num_faces());
    for (int f = 0; f < here->object.num_faces(); ++f) {
      ASSERT_EQ(there->object.face(f).vertices, here->object.face(f).vertices);
      ASSERT_EQ(there->object.face(f).material, here->object.face(f).material);
      ASSERT_EQ(there->object.face(f).source_polygon, here->object.face(f).source_polygon);
    }
    EXPECT_TRUE(std::ranges::equal(there->object.materials(), here->object.materials()));
    EXPECT_EQ(there->cleaning.welded_vertices, here->cleaning.welded_vertices);
    EXPECT_EQ(there->cleaning.input_polygons, here->cleaning.input_polygons);
  }
}

// Files nested past any stack (the readers recurse) crash the worker, not
// this process, which reports the crash naming the file.
TEST(SandboxedImportTest, DeepNestingCrashesOnlyTheWorker) {
  constexpr int kDepth = 200000;
  std::string iv = "#Inventor V2.1 ascii\n";
  for (int i = 0; i < kDepth; ++i) iv += "Separator {\n";
  iv += "Cube {}\n" + std::string(kDepth, '}');
  std::string wrl = "#VRML V2.0 utf8\n";
  for (int i = 0; i < kDepth; ++i) wrl += "Transform { children [\n";
  for (int i = 0; i < kDepth; ++i) wrl += "] }";
  std::string dae =
      "<?xml version=\"1.0\"?><COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" "
      "version=\"1.4.1\"><library_visual_scenes><visual_scene id=\"s\">";
  for (int i = 0; i < kDepth; ++i) dae += "<node>";
  for (int i = 0; i < kDepth; ++i) dae += "</node>";
  dae += "</visual_scene></library_visual_scenes></COLLADA>";
  for (const auto& [name, text] :
       {std::pair{"deep.iv", iv}, {"deep.wrl", wrl}, {"deep.dae", dae}}) {
    const std::string path = Write(name, text);
    absl::StatusOr<ImportedModel> model = SandboxedImport(path);
    ASSERT_FALSE(model.ok()) << name;
    EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(model.status().message(), HasSubstr(path + ": ")) << model.status();
  }
}

// An 800-byte OFF file that crashes assimp 5.2's reader (found by
// import_fuzzer) costs the worker only.
TEST(SandboxedImportTest, FileThatCrashesAssimpCrashesOnlyTheWorker) {
  const std::string path = TestDataPath("crashes_assimp.off");
  absl::StatusOr<ImportedModel> model = SandboxedImport(path);
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(model.status().message(), HasSubstr(path + ": the importer crashed"));
}

// A glTF buffer or an Inventor File node naming a file outside the upload
// reads nothing: the import fails the same way whether the file exists
// (/etc/passwd) or not (/etc/nopass, as long a name), so the message tells
// nothing of it; no descriptor is left open, however many such imports.
TEST(SandboxedImportTest, ReferencesToOtherFilesReadNothing) {
  auto gltf = [](const std::string& target) {
    return Write("escape-" + target.substr(5) + ".gltf", R"({
      "asset": {"version": "2.0"},
      "buffers": [{"uri": "../../../../../../../..)" + target +
                                                             R"(", "byteLength": 36}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 1]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})");
  };
  auto iv = [](const std::string& target) {
    return Write("escape-" + target.substr(5) + ".iv",
                 "#Inventor V2.1 ascii\nFile { name \"" + target + "\" }\n");
  };
  // The message with the file and the name it refers to taken out.
  auto Message = [](const std::string& path, const std::string& target) {
    absl::StatusOr<ImportedModel> model = SandboxedImport(path);
    EXPECT_FALSE(model.ok()) << path;
    EXPECT_EQ(model.status().code(), absl::StatusCode::kInvalidArgument);
    std::string message(model.status().message());
    for (const std::string& name :
         {path, target, std::filesystem::path(path).filename().string()}) {
      for (size_t at; (at = message.find(name)) != std::string::npos;)
        message.replace(at, name.size(), "X");
    }
    return message;
  };
  const int before = OpenDescriptors();
  for (int round = 0; round < 20; ++round) {
    EXPECT_EQ(Message(gltf("/etc/passwd"), "/etc/passwd"),
              Message(gltf("/etc/nopass"), "/etc/nopass"));
    EXPECT_EQ(Message(iv("/etc/passwd"), "/etc/passwd"), Message(iv("/etc/nopass"), "/etc/nopass"));
  }
  EXPECT_EQ(OpenDescriptors(), before);
  // An OBJ's mtllib outside the upload is not read: the model imports with
  // the material names of its usemtl lines alone.
  const std::string obj = Write("escape.obj",
                                "mtllib /etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  absl::StatusOr<ImportedModel> obj_model = SandboxedImport(obj);
  ASSERT_TRUE(obj_model.ok()) << obj_model.status();
  for (const Material& m : obj_model->object.materials())
    EXPECT_THAT(m.name, Not(HasSubstr("root")));
}

// Too little memory ends the import with a message naming the file.
TEST(SandboxedImportTest, MemoryLimitEndsTheImport) {
  if (hs::testing::kSanitizedBuild) GTEST_SKIP() << "sanitized workers take no address-space limit";
  const std::string kidney = TestDataPath("kidney.obj");
  absl::StatusOr<ImportedModel> starved =
      SandboxedImport(kidney, {}, SandboxLimits{.memory_bytes = 16 << 20});
  ASSERT_FALSE(starved.ok());
  EXPECT_EQ(starved.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(starved.status().message(), HasSubstr(kidney));
}

// Too little wall time ends the import naming the file; a missing worker
// is UNAVAILABLE; a missing file NOT_FOUND.
TEST(SandboxedImportTest, WallTimeAndMissingPieces) {
  const std::string kidney = TestDataPath("kidney.obj");

  absl::StatusOr<ImportedModel> hurried =
      SandboxedImport(kidney, {}, SandboxLimits{.wall_s = 1e-6});
  ASSERT_FALSE(hurried.ok());
  EXPECT_THAT(hurried.status().message(), HasSubstr("took longer than"));

  absl::StatusOr<ImportedModel> missing = SandboxedImport(TestDataPath("no_such_file.obj"));
  EXPECT_EQ(missing.status().code(), absl::StatusCode::kNotFound) << missing.status();

  setenv("HAPTIC_IMPORT_WORKER", "/nonexistent/haptic-import", 1);
  absl::StatusOr<ImportedModel> no_worker = SandboxedImport(kidney);
  unsetenv("HAPTIC_IMPORT_WORKER");
  EXPECT_EQ(no_worker.status().code(), absl::StatusCode::kUnavailable) << no_worker.status();
}

}  // namespace
}  // namespace hs
