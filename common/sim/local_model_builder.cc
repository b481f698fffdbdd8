#include "common/sim/local_model_builder.h"

#include <algorithm>
#include <cmath>

#include "common/collision/faces_in_box.h"
#include "common/core/scratch.h"
#include "common/sim/motion_bounds.h"

namespace hs {
namespace {

// A triangle in the world frame with its unit normal (out of its object).
struct WorldFace {
  Vector3d a, b, c, n;
};

// Kept between steps (common/core/scratch.h): the faces near the tool, and
// the tool's vertices and faces at the proxy pose.
struct NearFeatures {
  std::vector<FaceId> faces;
  std::vector<VertexId> vertices;
  std::vector<EdgeId> edges;
};
struct ObjectNear {
  NearFeatures features;
};
struct ToolNear {
  NearFeatures features;
};
// An edge in the world frame: its ends and the sum of its faces' normals
// (which side is out).
struct WorldEdge {
  Vector3d from, to, out;
};
struct PlacedTool {
  std::vector<Vector3d> vertices;
  std::vector<WorldFace> faces;
  std::vector<WorldEdge> edges;
};
struct CandidatePlanes {
  std::vector<ConstraintPlane> planes;
};

// Two planes closer than these in direction (cosine) and offset (relative
// to the tool's size) are one: the two triangles of a flat face.
constexpr double kSameNormalCos = 1 - 1e-9;
constexpr double kSameOffset = 1e-9;

// Face `f` of `o` in the world frame; false when it has no area.
bool PlaceFace(const PosedObject& o, FaceId f, WorldFace& out) {
  const Face& face = o.object->face(f);
  out.a = o.X_WO * o.object->position(face.vertices[0]);
  out.b = o.X_WO * o.object->position(face.vertices[1]);
  out.c = o.X_WO * o.object->position(face.vertices[2]);
  const Vector3d normal = (out.b - out.a).cross(out.c - out.a);
  if (!(normal.norm() > 0)) return false;
  out.n = normal.normalized();
  return true;
}

// Whether `p` (on the face's plane) lies in the face, within `slack` of its
// edges (relative to the face's size).
bool Inside(const WorldFace& f, const Vector3d& p, double slack) {
  for (const auto& [from, to] : {std::pair{&f.a, &f.b}, {&f.b, &f.c}, {&f.c, &f.a}}) {
    const Vector3d edge = *to - *from;
    if (f.n.cross(edge).dot(p - *from) < -slack * edge.squaredNorm()) return false;
  }
  return true;
}

// Unit normal of face `f` of `o` in the world frame (zero when it has no
// area).
Vector3d FaceNormal(const PosedObject& o, FaceId f) {
  WorldFace face;
  return PlaceFace(o, f, face) ? face.n : Vector3d::Zero();
}

// Edge `e` of `o` in the world frame.
WorldEdge PlaceEdge(const PosedObject& o, EdgeId e) {
  const Edge& edge = o.object->edge(e);
  WorldEdge out{o.X_WO * o.object->position(edge.vertices[0]),
                o.X_WO * o.object->position(edge.vertices[1]), Vector3d::Zero()};
  for (const FaceId f : o.object->EdgeFaces(e)) out.out += FaceNormal(o, f);
  return out;
}

// The plane where tool edge `t` meets object edge `o` when the tool moves
// along it: normal t x o, out of the object and into neither side's
// faces; the closest points of the lines must lie on both edges. False
// for parallel edges (the vertex pairs hold those) and edges that cannot
// meet that way.
bool EdgePairPlane(const WorldEdge& t, const WorldEdge& o, ConstraintPlane& plane) {
  const Vector3d u = t.to - t.from, v = o.to - o.from;
  Vector3d n = u.cross(v);
  if (!(n.norm() > 1e-9 * u.norm() * v.norm())) return false;
  n.normalize();
  if (n.dot(o.out) < 0) n = -n;
  if (!(n.dot(o.out) > 0 && n.dot(t.out) < 0)) return false;
  // Closest points of the two lines: t.from + a u and o.from + b v.
  const Vector3d w = t.from - o.from;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
  const double det = uu * vv - uv * uv;
  const double a = (uv * vw - vv * uw) / det, b = (uu * vw - uv * uw) / det;
  constexpr double kEnds = 1e-9;
  if (a < -kEnds || a > 1 + kEnds || b < -kEnds || b > 1 + kEnds) return false;
  const Vector3d on_tool = t.from + a * u, on_object = o.from + b * v;
  plane.normal_W = n;
  plane.gap_m = n.dot(on_tool - on_object);
  plane.point_W = on_object;
  plane.tool_point_W = on_tool;
  return true;
}

template <typename T>
void SortUnique(std::vector<T>& ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

// The faces of `o` whose volumes meet `box_W`, and their vertices and edges,
// each once, sorted (the same model whatever the traversal order).
// Returns the world box of those faces.
AlignedBox3d FindNearFeatures(const PosedObject& o, const AlignedBox3d& box_W, NearFeatures& out) {
  out.faces.clear();
  out.vertices.clear();
  out.edges.clear();
  FindFacesInBox(*o.model, o.X_WO, box_W, out.faces);
  SortUnique(out.faces);
  for (const FaceId f : out.faces) {
    const Face& face = o.object->face(f);
    out.vertices.insert(out.vertices.end(), face.vertices.begin(), face.vertices.end());
    out.edges.insert(out.edges.end(), face.edges.begin(), face.edges.end());
  }
  SortUnique(out.vertices);
  SortUnique(out.edges);
  AlignedBox3d box;
  for (const VertexId v : out.vertices) box.extend(o.X_WO * o.object->position(v));
  return box;
}

// A plane of object `id` with the material of its face `f`.
ConstraintPlane MaterialPlane(const HapticObject& object, FaceId f, ObjectId id) {
  const Material& m = object.face_material(f);
  return {.object = id,
          .stiffness_n_per_m = m.stiffness_n_per_m,
          .damping_ns_per_m = m.damping_ns_per_m,
          .static_friction = m.static_friction,
          .dynamic_friction = m.dynamic_friction};
}

// Whether `a` and `b` are one plane.
bool SamePlane(const ConstraintPlane& a, const ConstraintPlane& b, double size) {
  return a.normal_W.dot(b.normal_W) > kSameNormalCos &&
         std::abs(a.normal_W.dot(a.point_W - b.point_W)) <= kSameOffset * size;
}

// Nearest first; ties in a fixed order, so that the model does not depend
// on the order the pairs were found in.
bool Nearer(const ConstraintPlane& x, const ConstraintPlane& y) {
  if (x.gap_m != y.gap_m) return x.gap_m < y.gap_m;
  for (int i = 0; i < 3; ++i) {
    if (x.normal_W[i] != y.normal_W[i]) return x.normal_W[i] < y.normal_W[i];
  }
  for (int i = 0; i < 3; ++i) {
    if (x.tool_point_W[i] != y.tool_point_W[i]) return x.tool_point_W[i] < y.tool_point_W[i];
  }
  return x.object < y.object;
}

// The tool's `near` features at X_WP in the world frame.
void PlaceTool(const HapticObject& t, const Isometry3d& X_WP, const NearFeatures& near,
               PlacedTool& placed) {
  const PosedObject at_proxy{&t, nullptr, X_WP};
  placed.vertices.clear();
  for (const VertexId v : near.vertices) placed.vertices.push_back(X_WP * t.position(v));
  placed.faces.clear();
  for (const FaceId g : near.faces) {
    WorldFace face;
    if (PlaceFace(at_proxy, g, face)) placed.faces.push_back(face);
  }
  placed.edges.clear();
  for (const EdgeId e : near.edges) placed.edges.push_back(PlaceEdge(at_proxy, e));
}

}  // namespace

void BuildLocalModel(const PosedObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                     std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                     const LocalModelOptions& options, LocalModel& model) {
  model.X_WP = proxy.X_WP;
  model.p_WD = p_WD;
  model.validity_radius_m = options.radius_m;
  model.force_clamp_n = options.force_clamp_n;
  model.friction = options.friction;
  model.touching = proxy.touching;
  model.touch_point_W = proxy.touching ? proxy.p_WC : proxy.X_WP.translation();
  model.planes.clear();
  const HapticObject& t = *tool.object;
  const double size = t.bounding_box().diagonal().norm();
  // A pair this far behind its plane (the proxy's stand-off is 1e-6 of the
  // size in front) is not one the tool rests on.
  const double behind = 1e-6 * size;
  constexpr double kSlack = 1e-9;
  PlacedTool& placed = Scratch<PlacedTool>();
  const PosedObject at_proxy{tool.object, tool.model, proxy.X_WP};
  const AlignedBox3d near = GrowBox(WorldBox(t, proxy.X_WP), options.radius_m);
  std::vector<ConstraintPlane>& candidates = Scratch<CandidatePlanes>().planes;
  candidates.clear();
  NearFeatures& object_near = Scratch<ObjectNear>().features;
  NearFeatures& tool_near = Scratch<ToolNear>().features;
  const std::vector<FaceId>& faces = object_near.faces;
  const std::vector<VertexId>& vertices = object_near.vertices;
  const std::vector<EdgeId>& edges = object_near.edges;
  // The planes of the translations the tool may make (the faces of the
  // obstacle in configuration space): where a vertex of the tool meets a
  // face of an object (the face's plane), where a vertex of an object
  // meets a face of the tool (the tool face's plane, turned round), and
  // where an edge of each meets (the plane of both). Each pair counts when
  // its features, moved along the plane's normal, would meet, and lie in
  // front by at most the radius.
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PosedObject& o = obstacles[k];
    // The object's features near the tool, and the tool's near those: on
    // both sides only what may meet within the radius.
    const AlignedBox3d object_box = FindNearFeatures(o, near, object_near);
    if (object_box.isEmpty()) continue;
    FindNearFeatures(at_proxy, GrowBox(object_box, options.radius_m), tool_near);
    PlaceTool(t, proxy.X_WP, tool_near, placed);
    for (const FaceId f : faces) {  // tool vertex, object face
      WorldFace face;
      if (!PlaceFace(o, f, face)) continue;
      ConstraintPlane plane = MaterialPlane(*o.object, f, ids[k]);
      for (const Vector3d& v : placed.vertices) {
        const double gap = face.n.dot(v - face.a);
        if (gap < -behind || gap > options.radius_m) continue;
        const Vector3d on_face = v - gap * face.n;
        if (!Inside(face, on_face, kSlack)) continue;
        plane.normal_W = face.n;
        plane.gap_m = std::max(gap, 0.0);
        plane.point_W = on_face;
        plane.tool_point_W = v;
        candidates.push_back(plane);
      }
    }
    // Features beyond the box are farther than the radius from the tool:
    // a move the model holds for cannot bring them together.
    for (const VertexId v : vertices) {  // object vertex, tool face
      const Vector3d q = o.X_WO * o.object->position(v);
      if (!near.contains(q)) continue;
      ConstraintPlane plane = MaterialPlane(*o.object, o.object->VertexFaces(v).front(), ids[k]);
      for (const WorldFace& g : placed.faces) {
        const double gap = g.n.dot(q - g.a);
        if (gap < -behind || gap > options.radius_m) continue;
        const Vector3d on_tool = q - gap * g.n;
        if (!Inside(g, on_tool, kSlack)) continue;
        plane.normal_W = -g.n;
        plane.gap_m = std::max(gap, 0.0);
        plane.point_W = q;
        plane.tool_point_W = on_tool;
        candidates.push_back(plane);
      }
    }
    for (const EdgeId e : edges) {  // object edge, tool edge
      const Edge& ends = o.object->edge(e);
      AlignedBox3d box(o.X_WO * o.object->position(ends.vertices[0]));
      box.extend(o.X_WO * o.object->position(ends.vertices[1]));
      if (!box.intersects(near)) continue;
      const WorldEdge edge = PlaceEdge(o, e);
      ConstraintPlane plane = MaterialPlane(*o.object, o.object->EdgeFaces(e).front(), ids[k]);
      for (const WorldEdge& g : placed.edges) {
        if (!EdgePairPlane(g, edge, plane)) continue;
        if (plane.gap_m < -behind || plane.gap_m > options.radius_m) continue;
        plane.gap_m = std::max(plane.gap_m, 0.0);
        candidates.push_back(plane);
      }
    }
  }
  // The nearest distinct planes, at most max_planes.
  std::sort(candidates.begin(), candidates.end(), Nearer);
  for (const ConstraintPlane& plane : candidates) {
    if (static_cast<int>(model.planes.size()) == options.max_planes) break;
    const bool seen =
        std::any_of(model.planes.begin(), model.planes.end(),
                    [&](const ConstraintPlane& p) { return SamePlane(p, plane, size); });
    if (!seen) model.planes.push_back(plane);
  }
}

void ReanchorLocalModel(const LocalModel& built, const ProxyState& proxy, const Vector3d& p_WD,
                        double moved_m, double behind_m, LocalModel& model) {
  const Vector3d shift = proxy.X_WP.translation() - built.X_WP.translation();
  model.revision = built.revision;
  model.X_WP = proxy.X_WP;
  model.p_WD = p_WD;
  model.validity_radius_m = std::max(built.validity_radius_m - moved_m, behind_m);
  model.force_clamp_n = built.force_clamp_n;
  model.friction = built.friction;
  model.touching = proxy.touching;
  model.touch_point_W = proxy.touching ? proxy.p_WC : proxy.X_WP.translation();
  model.planes.clear();
  for (const ConstraintPlane& plane : built.planes) {
    // The tool's point moved with the proxy: its gap in front of the plane
    // changed by the shift along the normal.
    const double gap = plane.gap_m + plane.normal_W.dot(shift);
    if (gap < -behind_m) continue;
    model.planes.push_back(plane);
    model.planes.back().gap_m = std::max(gap, 0.0);
    model.planes.back().tool_point_W = plane.tool_point_W + shift;
  }
}

}  // namespace hs
