#include "common/hds/weld.h"

#include <cmath>
#include <unordered_map>

#include "common/core/check.h"

namespace hs {
namespace {

struct CellHash {
  size_t operator()(const Eigen::Array3i& c) const {
    return (static_cast<size_t>(c[0]) * 73856093u) ^ (static_cast<size_t>(c[1]) * 19349663u) ^
           (static_cast<size_t>(c[2]) * 83492791u);
  }
};
struct CellEqual {
  bool operator()(const Eigen::Array3i& a, const Eigen::Array3i& b) const { return (a == b).all(); }
};

}  // namespace

std::vector<VertexId> FindWeldTargets(std::span<const Vector3d> positions, double tolerance) {
  HS_CHECK(tolerance >= 0);
  const int n = static_cast<int>(positions.size());
  std::vector<VertexId> target(n);
  if (n == 0) return target;
  // A uniform grid with cells no smaller than the tolerance: a vertex's
  // duplicates lie in its own cell or one of the 26 around it. The cell is
  // never smaller than 1e-6 of the extent so that cell indices fit an int.
  AlignedBox3d box;
  for (const Vector3d& p : positions) box.extend(p);
  const double cell =
      std::max({tolerance, box.sizes().maxCoeff() * 1e-6, std::numeric_limits<double>::min()});
  std::unordered_map<Eigen::Array3i, std::vector<VertexId>, CellHash, CellEqual> grid;
  grid.reserve(n);
  for (VertexId v = 0; v < n; ++v) {
    const Eigen::Array3i c = ((positions[v] - box.min()) / cell).array().floor().cast<int>();
    // Only kept vertices are in the grid; the smallest one in reach wins.
    target[v] = v;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(c + Eigen::Array3i(dx, dy, dz));
          if (it == grid.end()) continue;
          for (VertexId u : it->second) {
            if (u < target[v] && (positions[u] - positions[v]).norm() <= tolerance) target[v] = u;
          }
        }
      }
    }
    if (target[v] == v) grid[c].push_back(v);
  }
  return target;
}

}  // namespace hs
