#include "tests/bench/subdivided_model.h"

#include <assimp/Subdivision.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <memory>

#include "absl/strings/str_cat.h"

namespace hs::accuracy {

// assimp's own Catmull-Clark rather than a subdivision written here: it is
// the library the importer already trusts, it handles extraordinary
// vertices and creases of any control mesh, and a benchmark reference
// should not rest on untested geometry code of its own. assimp stays in
// this bench-only file, behind a model file, as common/model keeps it.
absl::Status WriteSubdividedObj(const std::string& path, int levels, const std::string& out_path) {
  try {
    Assimp::Importer importer;
    // No post-processing: the OBJ reader's one vertex per face corner is
    // the "verbose format" the subdivider requires.
    if (importer.ReadFile(path, 0) == nullptr) {
      return absl::InvalidArgumentError(absl::StrCat(path, ": ", importer.GetErrorString()));
    }
    std::unique_ptr<aiScene> scene(importer.GetOrphanedScene());
    if (scene->mNumMeshes != 1) {
      return absl::InvalidArgumentError(absl::StrCat(path, ": ", scene->mNumMeshes, " meshes"));
    }
    std::unique_ptr<Assimp::Subdivider> subdivider(
        Assimp::Subdivider::Create(Assimp::Subdivider::CATMULL_CLARKE));
    aiMesh* refined = nullptr;
    subdivider->Subdivide(scene->mMeshes[0], refined, static_cast<unsigned>(levels),
                          /*discard_input=*/true);
    scene->mMeshes[0] = refined;
    Assimp::Exporter exporter;
    if (exporter.Export(scene.get(), "objnomtl", out_path) != AI_SUCCESS) {
      return absl::InternalError(absl::StrCat(out_path, ": ", exporter.GetErrorString()));
    }
    return absl::OkStatus();
  } catch (const std::exception& e) {
    return absl::InternalError(absl::StrCat(path, ": ", e.what()));
  }
}

}  // namespace hs::accuracy
