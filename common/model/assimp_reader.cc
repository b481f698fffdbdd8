#include "common/model/assimp_reader.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <filesystem>
#include <limits>
#include <utility>
#include <vector>

#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

Eigen::Matrix4d ToEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

bool HasExtension(const std::string& path, const std::string& lower_extension) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == lower_extension;
}

// The turn assimp's DXF importer (5.2) puts on the root node to go from
// AutoCAD's Z-up to its own Y-up convention.
bool IsDxfUpTurn(const aiMatrix4x4& m) {
  return m == aiMatrix4x4(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1);
}

std::vector<std::string> MaterialNames(const aiScene& scene) {
  std::vector<std::string> names(scene.mNumMaterials);
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    aiString name;
    if (scene.mMaterials[i] != nullptr &&
        scene.mMaterials[i]->Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS &&
        std::string(name.C_Str()) != AI_DEFAULT_MATERIAL_NAME) {
      names[i] = name.C_Str();
    }
  }
  // Every polygon names a material, also in a file without one.
  if (names.empty()) names.emplace_back();
  return names;
}

// Appends one instance of `mesh`, placed by X_RM (mesh frame in root frame).
absl::Status AppendMesh(const aiMesh& mesh, const Eigen::Matrix4d& X_RM, int32_t num_materials,
                        RawMesh& out, PolygonId& next_polygon) {
  constexpr size_t kMaxIndex = std::numeric_limits<int32_t>::max();
  if (out.positions.size() + mesh.mNumVertices > kMaxIndex) {
    return absl::InvalidArgumentError("more than 2^31 - 1 vertices");
  }
  const auto base = static_cast<int32_t>(out.positions.size());
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D& p = mesh.mVertices[v];
    const Eigen::Vector4d p_R = X_RM * Eigen::Vector4d(p.x, p.y, p.z, 1.0);
    out.positions.push_back(p_R.head<3>() / p_R.w());
  }
  // A mirroring transform turns counter-clockwise into clockwise.
  const bool mirrored = X_RM.topLeftCorner<3, 3>().determinant() < 0;
  const int32_t material =
      static_cast<int32_t>(mesh.mMaterialIndex) < num_materials ? mesh.mMaterialIndex : 0;
  std::vector<int32_t> corners;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices < 3) continue;  // a point or a line: nothing to touch
    corners.clear();
    for (unsigned i = 0; i < face.mNumIndices; ++i) {
      if (face.mIndices[i] >= mesh.mNumVertices) {
        return absl::InvalidArgumentError(absl::StrCat("face ", f, " of mesh '", mesh.mName.C_Str(),
                                                       "' names vertex ", face.mIndices[i],
                                                       " but there are ", mesh.mNumVertices));
      }
      corners.push_back(base + static_cast<int32_t>(face.mIndices[i]));
    }
    if (mirrored) std::reverse(corners.begin(), corners.end());
    if (out.corners.size() + corners.size() > kMaxIndex) {
      return absl::InvalidArgumentError("more than 2^31 - 1 polygon corners");
    }
    out.AddPolygon(corners, material, next_polygon++);
  }
  return absl::OkStatus();
}

absl::StatusOr<RawMesh> ToRawMesh(const aiScene& scene, bool is_dxf) {
  RawMesh out;
  out.material_names = MaterialNames(scene);
  const auto num_materials = static_cast<int32_t>(out.material_names.size());
  PolygonId next_polygon = 0;
  if (scene.mRootNode == nullptr) return out;
  // Depth-first with an explicit stack: node trees can be deep.
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack;
  Eigen::Matrix4d X_RootRoot = ToEigen(scene.mRootNode->mTransformation);
  if (is_dxf && IsDxfUpTurn(scene.mRootNode->mTransformation)) {
    X_RootRoot.setIdentity();
  }
  stack.emplace_back(scene.mRootNode, X_RootRoot);
  while (!stack.empty()) {
    auto [node, X_RN] = std::move(stack.back());
    stack.pop_back();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned m = node->mMeshes[i];
      if (m >= scene.mNumMeshes || scene.mMeshes[m] == nullptr) {
        return absl::InvalidArgumentError(
            absl::StrCat("node '", node->mName.C_Str(), "' names missing mesh ", m));
      }
      absl::Status status = AppendMesh(*scene.mMeshes[m], X_RN, num_materials, out, next_polygon);
      if (!status.ok()) return status;
    }
    // Children pushed in reverse so that they come off the stack in order.
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren[c];
      if (child != nullptr) stack.emplace_back(child, X_RN * ToEigen(child->mTransformation));
    }
  }
  return out;
}

// Refuses every file: the only bytes a reader of a model's bytes alone
// gets are the ones in memory (assimp's MemoryIOSystem serves those and
// asks this for anything else, such as a glTF buffer or an OBJ mtllib).
class NoFilesIOSystem final : public Assimp::IOSystem {
 public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

// Reads with `read` (which calls ReadFile or ReadFileFromMemory on the
// importer it is given) and turns the scene into a RawMesh.
template <class Read>
absl::StatusOr<RawMesh> ReadScene(Assimp::Importer& importer, Read read, bool dxf) {
  try {
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    // No aiProcess_Triangulate: polygons stay whole so that every triangle
    // can name its file polygon. No aiProcess_JoinIdenticalVertices either:
    // cleaning welds and reports what it welded.
    const aiScene* scene = read(importer);
    if (scene == nullptr) {
      return absl::InvalidArgumentError(absl::StrCat("assimp: ", importer.GetErrorString()));
    }
    // Some readers "succeed" on garbage with an empty scene.
    if (scene->mNumMeshes == 0) {
      return absl::InvalidArgumentError("no triangles: assimp found no mesh in it");
    }
    scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure);
    if (scene == nullptr) {
      return absl::InvalidArgumentError(absl::StrCat("assimp: ", importer.GetErrorString()));
    }
    return ToRawMesh(*scene, dxf);
  } catch (const std::exception& e) {
    return absl::InvalidArgumentError(absl::StrCat("assimp threw: ", e.what()));
  } catch (...) {
    return absl::InvalidArgumentError("assimp threw an unknown exception");
  }
}

}  // namespace

absl::StatusOr<RawMesh> ReadWithAssimp(const std::string& path) {
  Assimp::Importer importer;
  return ReadScene(
      importer, [&](Assimp::Importer& i) { return i.ReadFile(path, 0); },
      HasExtension(path, ".dxf"));
}

absl::StatusOr<RawMesh> ReadBytesWithAssimp(absl::string_view bytes, const std::string& file_name) {
  Assimp::Importer importer;
  importer.SetIOHandler(new NoFilesIOSystem());  // the importer owns it
  std::string hint = std::filesystem::path(file_name).extension().string();
  if (!hint.empty()) hint.erase(0, 1);
  return ReadScene(
      importer,
      [&](Assimp::Importer& i) {
        return i.ReadFileFromMemory(bytes.data(), bytes.size(), 0, hint.c_str());
      },
      HasExtension(file_name, ".dxf"));
}

}  // namespace hs
