#pragma once
// QuickTrianglesTest (triangle_sat.h) of many face pairs, several at a
// time in the lanes of the machine's widest vectors (Google Highway, the
// target chosen when the program runs): bit for bit the scalar test, pair
// by pair. Most of the pairs a query tests are answered by it: a face's
// plane keeps them apart, they cross clearly, or an edge cross keeps them
// apart.

#include <span>

#include "common/collision/triangle_pairs.h"
#include "common/collision/triangle_sat.h"

namespace hs {

struct PlacedFace;  // common/collision/placed_faces.h, which holds FCL types

/// out[i] = QuickTrianglesTest of faces_a[pairs[i].a] and
/// faces_b[pairs[i].b] (each face's triangle and normal), at `margin`,
/// with or without `edge_cross`, for each i; `out` holds pairs.size()
/// entries. With `edge_cross`, every pair's face planes are tested before
/// any crossing test: for pairs most of which a plane keeps apart.
void QuickTrianglesTestBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                             std::span<const TrianglePair> pairs, double margin, bool edge_cross,
                             std::span<QuickTriangleTest> out);

}  // namespace hs
