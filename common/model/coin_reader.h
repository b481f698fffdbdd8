#pragma once
// Reading Open Inventor (.iv) and VRML 1.0 / 2.0 (.wrl) files with Coin3D,
// the formats of the paper's pipeline that assimp 5.2 cannot read. Internal
// to common/model.

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/model/raw_mesh.h"

namespace hs {

/// Reads the file at `path` with Coin (SoDB::readAll) and collects the
/// triangles of every shape (SoCallbackAction triangle callbacks), model
/// matrices applied in double. Coin triangulates; the RawMesh holds
/// triangles.
///
/// Provenance: for face-based shapes (IndexedFaceSet of Inventor, VRML 1 and
/// VRML 2, FaceSet, ...) Coin hands every triangle an SoFaceDetail whose
/// getFaceIndex() is the index of the face within its shape node. Each
/// (shape traversal, face index) pair gets the next polygon id, so the
/// triangles of one file face share an id and ids are dense in traversal
/// order. A triangle without an SoFaceDetail is a polygon of its own.
///
/// Vertices: within one traversal of a shape, corners with the same
/// coordinates are one vertex (the shape's coordinate indices are not
/// reliably available per triangle corner); a shape used twice (DEF/USE) is
/// two copies.
///
/// Materials: the material in effect for a triangle is found through the
/// diffuse colour array Coin's SoLazyElement points at, which is the field
/// array of the SoMaterial or SoVRMLMaterial node that set it. A material is
/// one (node, index) pair: its name is the node's DEF name, with "_<index>"
/// appended when the node holds several values (per-face or per-vertex
/// binding, the index taken from the triangle's first corner); an unnamed
/// node gives "material_<n>", n counting the file's materials in order of
/// first use. Faces under no material node, or coloured by SoBaseColor, a
/// VRML Color node or vertex colours, get the default material ("").
///
/// Winding: triangles are reversed where the shape is declared clockwise
/// (SoShapeHints vertexOrdering CLOCKWISE, VRML ccw FALSE) and where the
/// model matrix mirrors, so that counter-clockwise seen from outside holds.
///
/// Coin does not bound-check the indices of the file, so coordIndex of
/// indexed shapes and startIndex + numVertices of FaceSets are checked here
/// before Coin walks them.
///
/// Coin's read errors are captured (nothing is printed) and go into the
/// status: INVALID_ARGUMENT when Coin cannot parse the file or an index is
/// out of range. Holds the process-wide Coin lock while it runs. Does not
/// throw.
absl::StatusOr<RawMesh> ReadWithCoin(const std::string& path);

/// ReadWithCoin for a file's bytes alone, read from memory. Coin still
/// opens what an Inventor File node names: run it where opening files is
/// refused (the import sandbox) when the bytes are not trusted.
absl::StatusOr<RawMesh> ReadBytesWithCoin(absl::string_view bytes);

}  // namespace hs
