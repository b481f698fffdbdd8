#pragma once
// EdgeLinesMayMeet (edge_pairs.h) of one tool edge and many object edges,
// several at a time in the lanes of the machine's widest vectors (Google
// Highway, the target chosen when the program runs): the scalar test's
// answer, edge by edge. Most of the object edges a face search meets near
// a tool edge are turned away by it.

#include <array>
#include <span>
#include <vector>

#include "common/sim/edge_pairs.h"

namespace hs {

/// Object edges as columns of doubles, an edge a row: its start, its
/// vector (end - start) and its length.
class EdgeColumns {
 public:
  enum Column { kFromX, kFromY, kFromZ, kAlongX, kAlongY, kAlongZ, kLength, kNumColumns };

  void Clear();
  /// Adds the row of edge `e` of length `length_m`.
  void Add(const WorldEdge& e, double length_m);
  size_t size() const { return columns_[0].size(); }
  const double* column(Column c) const { return columns_[c].data(); }

 private:
  std::array<std::vector<double>, kNumColumns> columns_;
};

/// Of the rows `candidates` of `edges`, those whose edge EdgeLinesMayMeet
/// keeps with the tool edge from `t_from` along `u` (length `lu`) under
/// `move`, in the order given, into `kept` (room for candidates.size());
/// returns how many.
size_t KeepEdgesWhoseLinesMayMeet(const Vector3d& t_from, const Vector3d& u, double lu,
                                  const EdgeColumns& edges, std::span<const int> candidates,
                                  const EdgeMove& move, int* kept);

}  // namespace hs
