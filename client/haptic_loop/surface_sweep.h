#pragma once
// A device loop's sweep of its tool against a local model's surface
// (common/sim/local_model.h, ModelSurface): the first time a convex tool,
// moved by a straight translation, meets one of the surface's triangles,
// and the normal it meets it along. By separating axes over the time of
// the move (Gottschalk 2000; Eberly, "Intersection of convex objects: the
// method of separating axes"): on each candidate axis (the tool's face
// normals, the triangle's normal, and each tool edge crossed with each
// triangle edge) the move overlaps the two shadows over one interval of
// time; the tool meets the triangle at the latest start of those
// intervals, if it comes before their earliest end, and along the axis
// that starts it. Written by hand: a vendor's loop links Eigen alone, and
// none of its libraries sweeps a polyhedron against a triangle.

#include <limits>
#include <vector>

#include "common/core/types.h"
#include "common/sim/local_model.h"

namespace hs {

class SurfaceSweep {
 public:
  /// Holds room for the largest surface (local_model.h's caps): Set and
  /// Orient allocate nothing after.
  SurfaceSweep();
  /// A copy holds room for the largest surface too.
  SurfaceSweep(const SurfaceSweep& other) : SurfaceSweep() { *this = other; }
  SurfaceSweep& operator=(const SurfaceSweep&) = default;
  /// Takes `surface`'s tool and faces (surface.has_body(); indices within
  /// range and sizes within the caps, as LocalModelFromProto checks): the
  /// tool's axes (face normals and edge directions, parallel ones once)
  /// and each face's normal, edges and box.
  void Set(const ModelSurface& surface);
  /// Turns the tool to R_WT (world from tool) for the next sweeps.
  void Orient(const Matrix3d& R_WT);

  struct Touch {
    int triangle = -1;  ///< -1: none
    double t = std::numeric_limits<double>::infinity();
    /// Unit, world frame, out of the triangle toward the tool.
    Vector3d normal_W = Vector3d::Zero();
  };
  /// The first triangle the tool (its origin at `p`, world frame) meets
  /// moving by `v`, at t in [0, 1] of the move. A triangle it already
  /// overlaps is met at t = 0 when the move goes on into it along the axis
  /// it overlaps least (by distance), and not when the move leaves it.
  Touch First(const Vector3d& p, const Vector3d& v) const;
  /// Whether the tool at `p` overlaps any triangle by more than `depth_m`
  /// along every axis.
  bool Overlaps(const Vector3d& p, double depth_m) const;
  /// The tool's point that reaches farthest against `n` with its origin
  /// at `p` (the mean of its vertices within rounding of that): where it
  /// touches a face of normal `n`.
  Vector3d TouchPoint(const Vector3d& p, const Vector3d& n) const;
  /// Triangle `i`'s material.
  const ModelMaterial& Material(int triangle) const {
    return materials_[triangle_materials_[triangle]];
  }
  int size() const { return static_cast<int>(faces_.size()); }
  /// The diagonal of the tool's box in its own frame, metres.
  double tool_size() const { return tool_size_; }

 private:
  struct Face {
    Vector3d a, b, c;
    Vector3d normal;  // unit; zero for a face without area
    Vector3d edges[3];
    AlignedBox3d box;
  };
  // The tool's shadow on unit axis `axis` about its origin.
  void Shadow(const Vector3d& axis, double& low, double& high) const;
  // The sweep against one face: its touch time in `enter` (< 0 for an
  // overlap at the start) and its normal; false for none.
  bool Sweep(const Face& face, const Vector3d& p, const Vector3d& v, double& enter,
             Vector3d& normal) const;

  std::vector<Vector3d> vertices_T_, normals_T_, edges_T_;
  // Turned to the last Orient.
  std::vector<Vector3d> vertices_W_, normals_W_, edges_W_;
  // Per tool normal, its shadow about the origin.
  std::vector<double> normal_low_, normal_high_;
  // The tool's box about its origin, turned; its size unturned.
  AlignedBox3d tool_box_;
  double tool_size_ = 0;
  std::vector<Face> faces_;
  std::vector<int32_t> triangle_materials_;
  std::vector<ModelMaterial> materials_;
};

}  // namespace hs
