#pragma once
// QuickTrianglesTest (triangle_sat.h) of many face pairs, several at a
// time in the lanes of the machine's widest vectors (Google Highway, the
// target chosen when the program runs): bit for bit the scalar test, pair
// by pair. Most of the pairs a query tests are answered by it: a face's
// plane keeps them apart, they cross clearly, or an edge cross keeps them
// apart.

#include <cstdint>
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

/// apart[i]: whether a face's plane keeps faces_a[pairs[i].a] and
/// faces_b[pairs[i].b] beyond `margin`, bit for bit the plane tests
/// QuickTrianglesTest starts with (its kApart), for each i; `apart` holds
/// pairs.size() entries. A region's build keeps as candidates the pairs
/// no plane keeps apart.
void FacePlanesApartBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                          std::span<const TrianglePair> pairs, double margin,
                          std::span<uint8_t> apart);

/// For each i, EdgeCrossSeparates (triangle_sat.h) of the edge cross
/// hints[i].edge_pair (0-8) of faces_a[pairs[i].a] and faces_b[pairs[i].b]
/// at `margin`, bit for bit: separated[i] says whether it keeps them apart,
/// and hints[i] gets its gap and lever (0 where it does not), keeping its
/// edge pair. A coherent query's pairs that the quick test leaves are
/// mostly kept apart by the edge cross that kept them apart last time.
void HintedEdgeCrossBatch(const PlacedFace* faces_a, const PlacedFace* faces_b,
                          std::span<const TrianglePair> pairs, double margin,
                          std::span<PairHint> hints, std::span<uint8_t> separated);

}  // namespace hs
