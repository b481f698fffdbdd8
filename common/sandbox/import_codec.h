#pragma once
// ImportOptions and ImportedModel to and from the import worker's messages
// (proto/haptics/internal/import_job.proto). Internal to common/sandbox.

#include "absl/status/statusor.h"
#include "common/model/import.h"
#include "haptics/internal/import_job.pb.h"

namespace hs {

/// `options` into `job` (path and limits are set by the caller).
void OptionsToJob(const ImportOptions& options, haptics::internal::ImportJob& job);
/// The ImportOptions of `job`.
ImportOptions OptionsFromJob(const haptics::internal::ImportJob& job);

/// The mesh, materials and report of `model`.
haptics::internal::ImportedMesh MeshToProto(const ImportedModel& model);
/// The model `mesh` holds; INVALID_ARGUMENT when it is not a valid mesh
/// (as HapticObject::Create checks it).
absl::StatusOr<ImportedModel> MeshFromProto(const haptics::internal::ImportedMesh& mesh);

}  // namespace hs
