#include "client/haptic_loop/surface_sweep.h"

#include <algorithm>
#include <cmath>

namespace hs {
namespace {

// Unit directions closer to parallel than this (the sine of their angle)
// are one axis; a cross product of two edges that close is no axis.
constexpr double kParallelSine = 1e-9;

// Adds unit `d` to `axes` unless it or its opposite is there.
void AddAxis(const Vector3d& d, std::vector<Vector3d>& axes) {
  const double length = d.norm();
  if (!(length > 0)) return;
  const Vector3d unit = d / length;
  for (const Vector3d& a : axes) {
    if (a.cross(unit).norm() <= kParallelSine) return;
  }
  axes.push_back(unit);
}

}  // namespace

SurfaceSweep::SurfaceSweep() {
  // A hull's edges are at most three a triangle, its normals one.
  vertices_T_.reserve(kMaxToolHullVertices);
  vertices_W_.reserve(kMaxToolHullVertices);
  for (auto* axes : {&normals_T_, &normals_W_}) axes->reserve(kMaxToolHullTriangles);
  for (auto* axes : {&edges_T_, &edges_W_}) axes->reserve(3 * kMaxToolHullTriangles);
  normal_low_.reserve(kMaxToolHullTriangles);
  normal_high_.reserve(kMaxToolHullTriangles);
  faces_.reserve(kMaxSurfaceTriangles);
  triangle_materials_.reserve(kMaxSurfaceTriangles);
  materials_.reserve(kMaxSurfaceMaterials);
}

void SurfaceSweep::Set(const ModelSurface& surface) {
  vertices_T_.assign(surface.tool_vertices_T.begin(), surface.tool_vertices_T.end());
  AlignedBox3d box;
  for (const Vector3d& x : vertices_T_) box.extend(x);
  tool_size_ = box.isEmpty() ? 0 : box.diagonal().norm();
  normals_T_.clear();
  edges_T_.clear();
  for (const std::array<int32_t, 3>& t : surface.tool_triangles) {
    const Vector3d& a = vertices_T_[t[0]];
    const Vector3d& b = vertices_T_[t[1]];
    const Vector3d& c = vertices_T_[t[2]];
    AddAxis((b - a).cross(c - a), normals_T_);
    AddAxis(b - a, edges_T_);
    AddAxis(c - b, edges_T_);
    AddAxis(a - c, edges_T_);
  }
  faces_.resize(surface.triangles.size());
  for (size_t i = 0; i < faces_.size(); ++i) {
    const std::array<int32_t, 3>& t = surface.triangles[i];
    Face& f = faces_[i];
    f.a = surface.vertices_W[t[0]];
    f.b = surface.vertices_W[t[1]];
    f.c = surface.vertices_W[t[2]];
    const Vector3d n = (f.b - f.a).cross(f.c - f.a);
    f.normal = n.norm() > 0 ? Vector3d(n.normalized()) : Vector3d::Zero();
    const Vector3d sides[3] = {f.b - f.a, f.c - f.b, f.a - f.c};
    for (int k = 0; k < 3; ++k) {
      f.edges[k] = sides[k].norm() > 0 ? Vector3d(sides[k].normalized()) : Vector3d::Zero();
    }
    f.box = AlignedBox3d(f.a, f.a);
    f.box.extend(f.b);
    f.box.extend(f.c);
  }
  triangle_materials_.assign(surface.triangle_materials.begin(), surface.triangle_materials.end());
  materials_.assign(surface.materials.begin(), surface.materials.end());
  Orient(Matrix3d::Identity());
}

void SurfaceSweep::Orient(const Matrix3d& R_WT) {
  vertices_W_.resize(vertices_T_.size());
  normals_W_.resize(normals_T_.size());
  edges_W_.resize(edges_T_.size());
  for (size_t i = 0; i < vertices_T_.size(); ++i) vertices_W_[i] = R_WT * vertices_T_[i];
  for (size_t i = 0; i < normals_T_.size(); ++i) normals_W_[i] = R_WT * normals_T_[i];
  for (size_t i = 0; i < edges_T_.size(); ++i) edges_W_[i] = R_WT * edges_T_[i];
  normal_low_.resize(normals_W_.size());
  normal_high_.resize(normals_W_.size());
  for (size_t i = 0; i < normals_W_.size(); ++i)
    Shadow(normals_W_[i], normal_low_[i], normal_high_[i]);
  tool_box_.setEmpty();
  for (const Vector3d& x : vertices_W_) tool_box_.extend(x);
}

void SurfaceSweep::Shadow(const Vector3d& axis, double& low, double& high) const {
  low = std::numeric_limits<double>::infinity();
  high = -low;
  for (const Vector3d& x : vertices_W_) {
    const double s = axis.dot(x);
    low = std::min(low, s);
    high = std::max(high, s);
  }
}

namespace {

// One axis of a face's sweep: what the shadows of the tool (about its
// origin, [low, high]) and the face do along unit `axis` as the tool's
// origin goes from p to p + v.
struct AxisSweep {
  double enter = -std::numeric_limits<double>::infinity();
  double leave = std::numeric_limits<double>::infinity();
  Vector3d normal = Vector3d::Zero();  // of the latest start
  // At the start: the least overlap of the shadows and its direction.
  double depth = std::numeric_limits<double>::infinity();
  Vector3d depth_normal = Vector3d::Zero();

  // False when the shadows never overlap during the move.
  bool Narrow(const Vector3d& axis, double low, double high, const Vector3d& a, const Vector3d& b,
              const Vector3d& c, const Vector3d& p, const Vector3d& v) {
    const double at = axis.dot(p);
    const double tool_low = low + at, tool_high = high + at;
    const double fa = axis.dot(a), fb = axis.dot(b), fc = axis.dot(c);
    const double face_low = std::min({fa, fb, fc}), face_high = std::max({fa, fb, fc});
    // The overlap at the start, either way: the tool above the face's
    // shadow (pushed out along +axis) or below it.
    const double above = face_high - tool_low, below = tool_high - face_low;
    if (std::min(above, below) < depth) {
      depth = std::min(above, below);
      depth_normal = above <= below ? axis : Vector3d(-axis);
    }
    const double d = axis.dot(v);
    if (d == 0) return above >= 0 && below >= 0;
    // Coming down onto the face (d < 0) from above, or up from below.
    const double in = d < 0 ? above / d : -below / d;
    const double out = d < 0 ? (face_low - tool_high) / d : (face_high - tool_low) / d;
    if (in > enter) {
      enter = in;
      normal = d < 0 ? axis : Vector3d(-axis);
    }
    leave = std::min(leave, out);
    return enter <= leave;
  }
};

// Calls visit(axis, low, high) with each candidate separating axis of the
// tool and a face (unit), and the tool's shadow on it about its origin:
// the face's normal (none for a face without area), the tool's face
// normals (`lows`, `highs` their shadows), each tool edge crossed with
// each face edge (parallel ones skipped). False as soon as visit is.
template <class ShadowOf, class Visit>
bool WalkAxes(const Vector3d& face_normal, const Vector3d (&face_edges)[3],
              const std::vector<Vector3d>& normals, const std::vector<double>& lows,
              const std::vector<double>& highs, const std::vector<Vector3d>& edges, ShadowOf shadow,
              Visit visit) {
  double low, high;
  if (!face_normal.isZero()) {
    shadow(face_normal, low, high);
    if (!visit(face_normal, low, high)) return false;
  }
  for (size_t i = 0; i < normals.size(); ++i) {
    if (!visit(normals[i], lows[i], highs[i])) return false;
  }
  for (const Vector3d& e : edges) {
    for (const Vector3d& f : face_edges) {
      const Vector3d axis = e.cross(f);
      const double length = axis.norm();
      if (length <= kParallelSine) continue;
      const Vector3d unit = axis / length;
      shadow(unit, low, high);
      if (!visit(unit, low, high)) return false;
    }
  }
  return true;
}

}  // namespace

bool SurfaceSweep::Sweep(const Face& face, const Vector3d& p, const Vector3d& v, double& enter,
                         Vector3d& normal) const {
  AxisSweep s;
  const auto shadow = [this](const Vector3d& axis, double& low, double& high) {
    Shadow(axis, low, high);
  };
  if (!WalkAxes(face.normal, face.edges, normals_W_, normal_low_, normal_high_, edges_W_, shadow,
                [&](const Vector3d& axis, double low, double high) {
                  return s.Narrow(axis, low, high, face.a, face.b, face.c, p, v);
                })) {
    return false;
  }
  if (s.leave < 0 || s.enter > 1) return false;
  if (s.enter >= 0) {
    enter = s.enter;
    normal = s.normal;
    return true;
  }
  // Overlapping at the start: met only when the move goes on into the
  // face along the direction it overlaps least.
  if (!(s.depth_normal.dot(v) < 0)) return false;
  enter = 0;
  normal = s.depth_normal;
  return true;
}

SurfaceSweep::Touch SurfaceSweep::First(const Vector3d& p, const Vector3d& v) const {
  Touch first;
  if (tool_box_.isEmpty()) return first;
  AlignedBox3d swept(tool_box_.min() + p, tool_box_.max() + p);
  swept.extend(tool_box_.min() + p + v);
  swept.extend(tool_box_.max() + p + v);
  const double pad = 1e-9 * (swept.diagonal().norm() + p.cwiseAbs().maxCoeff());
  swept.min().array() -= pad;
  swept.max().array() += pad;
  for (int i = 0; i < size(); ++i) {
    const Face& face = faces_[i];
    if (!swept.intersects(face.box)) continue;
    double t;
    Vector3d n;
    if (Sweep(face, p, v, t, n) && t < first.t) first = {i, t, n};
  }
  return first;
}

bool SurfaceSweep::Overlaps(const Vector3d& p, double depth_m) const {
  if (tool_box_.isEmpty()) return false;
  const AlignedBox3d at(tool_box_.min() + p, tool_box_.max() + p);
  const auto shadow = [this](const Vector3d& axis, double& low, double& high) {
    Shadow(axis, low, high);
  };
  for (const Face& face : faces_) {
    if (!at.intersects(face.box)) continue;
    AxisSweep s;
    // In it by more than depth_m along every axis: no axis sets it apart.
    if (WalkAxes(face.normal, face.edges, normals_W_, normal_low_, normal_high_, edges_W_, shadow,
                 [&](const Vector3d& axis, double low, double high) {
                   (void)s.Narrow(axis, low, high, face.a, face.b, face.c, p, Vector3d::Zero());
                   return s.depth > depth_m;
                 })) {
      return true;
    }
  }
  return false;
}

Vector3d SurfaceSweep::TouchPoint(const Vector3d& p, const Vector3d& n) const {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vector3d& x : vertices_W_) lowest = std::min(lowest, n.dot(x));
  const double rounding = 1e-9 * tool_box_.diagonal().norm();
  Vector3d sum = Vector3d::Zero();
  int count = 0;
  for (const Vector3d& x : vertices_W_) {
    if (n.dot(x) <= lowest + rounding) {
      sum += x;
      ++count;
    }
  }
  return p + (count > 0 ? Vector3d(sum / count) : Vector3d::Zero());
}

}  // namespace hs
