#pragma once
// Meshes made from formulas: closed, consistently oriented (counter-clockwise
// seen from outside), one default material. They are the analytic shapes of
// tests, benchmarks and demo scenes.

#include "common/hds/haptic_object.h"

namespace hs {

/// Axis-aligned box centred at the origin with the given full side lengths
/// (metres, each > 0): 8 vertices, 12 faces; each side's two triangles share
/// one source polygon id.
MeshInput MakeBox(const Vector3d& size);

/// Sphere of `radius` metres from an icosahedron split `subdivisions` times:
/// 20 * 4^subdivisions faces, every vertex exactly on the sphere.
MeshInput MakeIcosphere(double radius, int subdivisions);

/// Torus around the z axis: tube centre circle of `major_radius`, tube of
/// `minor_radius` (< major_radius), `major_segments` x `minor_segments` quads
/// (each >= 3), each quad cut into two faces sharing a source polygon id.
MeshInput MakeTorus(double major_radius, double minor_radius, int major_segments,
                    int minor_segments);

/// `mesh` with every position p replaced by X * p.
MeshInput TransformMesh(MeshInput mesh, const Isometry3d& X);

/// One mesh holding both: b's vertex, material and polygon ids are shifted
/// past a's.
MeshInput MergeMeshes(MeshInput a, const MeshInput& b);

}  // namespace hs
