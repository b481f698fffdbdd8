#pragma once
// Reading model files with assimp: OBJ, STL, PLY, OFF, DXF, glTF 2, 3DS,
// COLLADA and the other formats assimp 5.2 knows. Internal to common/model.

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/model/raw_mesh.h"

namespace hs {

/// Reads every mesh of the file at `path` into one RawMesh, with the node
/// transforms applied (each instance of a mesh is its own copy), polygons
/// kept as polygons (no triangulation here) and point and line primitives
/// skipped. Polygon ids count the file's polygons in node order. Material
/// names come from AI_MATKEY_NAME; assimp's stand-in "DefaultMaterial" and
/// empty names become "" (the file names no material). File coordinates are
/// kept: COLLADA's up axis is ignored and the Z-up -> Y-up turn assimp puts on
/// DXF scenes is taken off.
/// INVALID_ARGUMENT with assimp's error string when assimp cannot read the
/// file. Does not throw: exceptions from assimp become INVALID_ARGUMENT.
absl::StatusOr<RawMesh> ReadWithAssimp(const std::string& path);

/// ReadWithAssimp for a file's bytes alone; `file_name`'s extension tells
/// assimp the format. No file is opened: a reference to another file (a
/// glTF buffer or image, an OBJ mtllib) finds nothing.
absl::StatusOr<RawMesh> ReadBytesWithAssimp(absl::string_view bytes, const std::string& file_name);

}  // namespace hs
