#pragma once
// Loading model files into the HDS. OBJ, STL (ascii and binary), PLY, OFF,
// DXF, glTF 2, 3DS, COLLADA and the other formats assimp reads go through
// assimp; Open Inventor (.iv) and VRML (.wrl), the formats of the paper's
// pipeline that assimp 5.2 cannot read, go through Coin3D.

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/hds/haptic_object.h"
#include "common/hds/material.h"

namespace hs {

/// How to read a model file into the HDS.
struct ImportOptions {
  /// Metres per file unit (0.001 for a file in millimetres). Finite and > 0.
  double unit_scale = 1.0;
  /// Vertices closer than this times the model's bounding-box diagonal are
  /// welded into one. Finite and >= 0; 0 welds exact duplicates only.
  double weld_relative_tolerance = 1e-6;
  /// Haptic parameters given to every material of the file; its name is used
  /// when the file has no material.
  Material default_material;
};

/// What cleaning changed between the file and the HDS. The vertex counts add
/// up: input_vertices == welded_vertices + dropped_unreferenced_vertices +
/// the object's vertices.
struct CleaningReport {
  /// Vertices as the reader delivered them. assimp gives OBJ, STL and DXF
  /// one vertex per face corner; Coin one per distinct point of each shape.
  int input_vertices = 0;
  /// Polygons of the file (a triangle counts as one polygon).
  int input_polygons = 0;
  /// Triangles after triangulating the polygons, before cleaning.
  int input_triangles = 0;
  /// Vertices merged into another one by welding.
  int welded_vertices = 0;
  /// Vertices no kept triangle uses, dropped.
  int dropped_unreferenced_vertices = 0;
  /// Triangles of zero area after welding (collapsed ones included), dropped.
  int dropped_degenerate_triangles = 0;
  /// Triangles over the same three vertices as an earlier one, dropped.
  int dropped_duplicate_triangles = 0;
};

/// One model file in the HDS and how it got there.
struct ImportedModel {
  HapticObject object;
  CleaningReport cleaning;
  /// The reader that read the file: "assimp" or "coin3d".
  std::string reader;
};

/// Reads the model file at `path` into one HapticObject named after the file
/// (its stem). The reader is chosen by extension, in any case: .iv and .wrl
/// go to Coin3D, everything else to assimp. Every mesh of the file is merged,
/// with the file's node transforms applied, in the file's coordinates times
/// options.unit_scale; polygons are triangulated (concave ones included) and
/// each face keeps the id of the file polygon it was cut from; faces are
/// counter-clockwise seen from outside when the file's are. Each material
/// name of the file that a kept face uses becomes one HDS material with the
/// haptic parameters of options.default_material. Cleaning (welding,
/// dropping degenerate and duplicate faces and unused vertices) is reported
/// in ImportedModel::cleaning. Thread-safe; never throws.
/// Errors (the message names the file and the reason):
///   NOT_FOUND           the file does not exist;
///   INVALID_ARGUMENT    bad options, or the file is unreadable, truncated,
///                       malformed, has non-finite coordinates or out-of-range
///                       indices, or has no triangle left after cleaning;
///   PERMISSION_DENIED   the file cannot be opened for reading.
absl::StatusOr<ImportedModel> ImportModel(const std::string& path,
                                          const ImportOptions& options = {});

/// ImportModel for a file's bytes alone, as if read from file `file_name`
/// (its extension picks the reader, its stem names the object). assimp
/// reads no other file (an OBJ mtllib, a glTF buffer finds nothing); Coin
/// still opens the files an Inventor File node names, so bytes from
/// elsewhere go through SandboxedImport (common/sandbox), which refuses
/// every open. Errors as ImportModel, INVALID_ARGUMENT for empty bytes.
absl::StatusOr<ImportedModel> ImportModelBytes(absl::string_view bytes,
                                               const std::string& file_name,
                                               const ImportOptions& options = {});

/// Sets up the readers' process-wide state (Coin's database) now rather
/// than on first use, so that reading later opens no file of its own.
void PrepareReaders();

}  // namespace hs
