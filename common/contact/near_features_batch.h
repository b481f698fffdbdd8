#pragma once
// Internal to common/contact: the contact locator's first tests
// (contact_features.cc) of many face pairs, several at a time in the lanes
// of the machine's widest vectors (Google Highway, the target chosen when
// the program runs): which corners and edges of each pair may lie within
// the tolerance of the other face. Most pairs a sweep leaves the locator
// touch at a corner of the moving face at most, well inside the fixed
// face's edges: these tests settle them, and the locator's exact tests
// run on the few features left.

#include <array>
#include <cstdint>
#include <span>

#include "common/collision/triangle_sat.h"

namespace hs {

/// `t`'s unit normal, (t[1] - t[0]) x (t[2] - t[0]) normalised; zero for a
/// degenerate face.
Vector3d UnitNormal(const Triangle3d& t);

/// A face's edges, each with its vector and box (edge i joins corners i
/// and i + 1).
struct FaceEdges {
  explicit FaceEdges(const Triangle3d& corners);
  std::array<Vector3d, 3> along, lo, hi;
};

/// A face of the moving object M in F's frame, with room to be loaded in
/// rows of four doubles.
struct MovingFaceCorners {
  Triangle3d corners;
  std::array<double, 3> padding{};
};

/// A face of the fixed object F with what the locator's tests of it need:
/// its corners, unit normal, the unit vector across each edge in the
/// face's plane (normal x edge: into the face; zero for a degenerate face
/// or edge), and the edges themselves. The first 24 doubles are what the
/// lanes load.
struct FixedFaceEdges {
  explicit FixedFaceEdges(const Triangle3d& corners);
  Triangle3d corners;
  Vector3d unit_normal;
  std::array<Vector3d, 3> across;
  std::array<double, 3> padding{};
  FaceEdges edges;
};

/// A face pair: indices into the moving and the fixed faces of a batch.
struct FaceRecordPair {
  int32_t moving, fixed;
};

/// What the first tests tell of a face pair (m of M, f of F), a bit for
/// each corner or edge i. Each test is the scalar comparison's, bit for
/// bit.
struct NearFeatures {
  /// m's corners within the tolerance of f's plane: |n_f . (m_i - f_0)| <=
  /// tolerance.
  uint8_t moving_corners = 0;
  /// m's edges whose two ends do not both lie beyond the tolerance on one
  /// side of f's plane.
  uint8_t moving_edges = 0;
  /// f's corners inside m's box grown by `corner_slack` on every side.
  uint8_t fixed_corners = 0;
  /// f's edges beside which m does not lie (every corner of m more than
  /// twice the tolerance on one side of the plane through the edge across
  /// it): none when no edge of m is near f's plane.
  uint8_t fixed_edges = 0;
};

/// out[i] = the first tests of moving[pairs[i].moving] and
/// fixed[pairs[i].fixed] at `tolerance` (metres) and `corner_slack`, for
/// each i; `out` holds pairs.size() entries.
void NearFeaturesBatch(const MovingFaceCorners* moving, const FixedFaceEdges* fixed,
                       std::span<const FaceRecordPair> pairs, double tolerance, double corner_slack,
                       std::span<NearFeatures> out);

}  // namespace hs
