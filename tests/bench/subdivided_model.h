#pragma once
// Finer versions of a committed model file for the accuracy sweep: the file
// refined by Catmull-Clark subdivision and written out as a new model file,
// so that every resolution still enters through the project's importer.

#include <string>

#include "absl/status/status.h"

namespace hs::accuracy {

/// Reads the one-mesh model file `path` with assimp, subdivides it `levels`
/// (>= 1) times by Catmull-Clark (each triangle becomes 3 quads, each quad
/// 4) and writes the result as a Wavefront OBJ of quads to `out_path`.
/// INVALID_ARGUMENT when the file cannot be read or holds other than one
/// mesh; INTERNAL when the OBJ cannot be written.
absl::Status WriteSubdividedObj(const std::string& path, int levels, const std::string& out_path);

}  // namespace hs::accuracy
