#include "common/sim/local_model_builder.h"

#include <algorithm>
#include <cmath>

#include "common/collision/faces_in_box.h"
#include "common/core/scratch.h"
#include "common/sim/motion_bounds.h"

namespace hs {
namespace {

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
struct PlacedTool {
  std::vector<Vector3d> vertices;
  std::vector<WorldFace> faces;
  std::vector<FaceId> face_ids;
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
// edges (relative to the face's size) and `margin_m` more.
bool Inside(const WorldFace& f, const Vector3d& p, double slack, double margin_m = 0) {
  for (const auto& [from, to] : {std::pair{&f.a, &f.b}, {&f.b, &f.c}, {&f.c, &f.a}}) {
    const Vector3d edge = *to - *from;
    const double squared = edge.squaredNorm();
    if (f.n.cross(edge).dot(p - *from) < -slack * squared - margin_m * std::sqrt(squared)) {
      return false;
    }
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
  for (int i = 0; i < 3; ++i) {
    if (x.point_W[i] != y.point_W[i]) return x.point_W[i] < y.point_W[i];
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
  placed.face_ids.clear();
  for (const FaceId g : near.faces) {
    WorldFace face;
    if (!PlaceFace(at_proxy, g, face)) continue;
    placed.faces.push_back(face);
    placed.face_ids.push_back(g);
  }
  placed.edges.clear();
  for (const EdgeId e : near.edges) placed.edges.push_back(PlaceEdge(at_proxy, e));
}

// Where point `p` falls on `face` along its normal (`foot`), and how far in
// front of it (`gap`): false when the gap is outside [-below_m, above_m] or
// the foot is off the face by more than `margin_m` (and rounding).
bool FootOnFace(const WorldFace& face, const Vector3d& p, double below_m, double above_m,
                double margin_m, Vector3d& foot, double& gap) {
  constexpr double kSlack = 1e-9;
  gap = face.n.dot(p - face.a);
  if (gap < -below_m || gap > above_m) return false;
  foot = p - gap * face.n;
  return Inside(face, foot, kSlack, margin_m);
}

// The index in `pairs.materials` of the plane template of face `f` of
// `object` (id `id`), added the first time (`index` < 0) and kept in
// `index` after.
int MaterialIndex(const HapticObject& object, FaceId f, ObjectId id, LocalModelPairs& pairs,
                  int& index) {
  if (index < 0) {
    index = static_cast<int>(pairs.materials.size());
    pairs.materials.push_back(MaterialPlane(object, f, id));
  }
  return index;
}

// Whether segments a and b may come within `within_m` of each other: their
// bounding balls do.
bool SegmentsMayMeet(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1,
                     double within_m) {
  const double half_a = 0.5 * (a1 - a0).norm(), half_b = 0.5 * (b1 - b0).norm();
  return (0.5 * (a0 + a1) - 0.5 * (b0 + b1)).norm() <= half_a + half_b + within_m;
}

// Whether tool edge `t` and object edge `o` may give a plane (EdgePairPlane,
// its gap in [-behind_m, radius_m]) once the tool has moved by at most
// `margin_m`, turning by at most `turn`: EdgePairPlane's tests, each
// loosened by what such a move may change. The plane's normal, across two
// edges at an angle whose sine is s, turns by at most turn / s (twice that
// here); the closest points slide along the edges by at most margin / s
// (thrice here); the lines' distance changes by at most twice the margin.
// Edges within four turns of parallel are kept whenever their balls may
// meet: their normal may turn any way. Without a margin, the test itself.
bool EdgePairMayGivePlane(const WorldEdge& t, const WorldEdge& o, double margin_m, double turn,
                          double radius_m, double behind_m) {
  if (margin_m == 0) {
    ConstraintPlane plane;
    return EdgePairPlane(t, o, plane) && plane.gap_m >= -behind_m && plane.gap_m <= radius_m;
  }
  const double apart_m = std::max(radius_m, behind_m) + 2 * margin_m;
  if (!SegmentsMayMeet(t.from, t.to, o.from, o.to, apart_m)) return false;
  const Vector3d u = t.to - t.from, v = o.to - o.from;
  const double lu = u.norm(), lv = v.norm();
  Vector3d n = u.cross(v);
  const double sine = n.norm() / (lu * lv);
  if (!(sine > 4 * turn + 1e-9)) return true;
  n.normalize();
  const double turned = 2 * turn / sine;
  const double out_o = o.out.norm(), out_t = t.out.norm();
  if (!(out_o > 0 && out_t > 0)) return false;
  const double along_o = n.dot(o.out) / out_o, along_t = n.dot(t.out) / out_t;
  const bool either = (along_o >= -turned && along_t <= turned + turn) ||
                      (-along_o >= -turned && -along_t <= turned + turn);
  if (!either) return false;
  const Vector3d w = t.from - o.from;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
  const double det = uu * vv - uv * uv;
  const double a = (uv * vw - vv * uw) / det, b = (uu * vw - uv * uw) / det;
  const double slide_m = 3 * margin_m / sine + 1e-9 * (lu + lv);
  if (a < -slide_m / lu || a > 1 + slide_m / lu || b < -slide_m / lv || b > 1 + slide_m / lv) {
    return false;
  }
  return std::abs(n.dot(t.from + a * u - o.from - b * v)) <= apart_m;
}

// How far behind its plane a pair may be and still count as touching: the
// proxy's stand-off is 1e-6 of the tool's size in front, so a pair farther
// behind is not one the tool rests on.
double Behind(const HapticObject& t) { return 1e-6 * t.bounding_box().diagonal().norm(); }

// The farthest corner of the tool's box from its origin.
double Reach(const HapticObject& t) {
  const AlignedBox3d box = t.bounding_box();
  double reach_m = 0;
  for (int corner = 0; corner < 8; ++corner) {
    reach_m = std::max(reach_m, box.corner(static_cast<AlignedBox3d::CornerType>(corner)).norm());
  }
  return reach_m;
}

// The tool's faces and edges placed at one proxy pose, each once however
// many pairs name it: `stamp` tells this placing's entries from older ones.
struct PlacedById {
  std::vector<WorldFace> faces;
  std::vector<bool> face_ok;
  std::vector<WorldEdge> edges;
  std::vector<uint64_t> face_stamp, edge_stamp;
  uint64_t stamp = 0;

  void Begin(const HapticObject& t) {
    ++stamp;
    faces.resize(t.num_faces());
    face_ok.resize(t.num_faces());
    face_stamp.resize(t.num_faces(), 0);
    edges.resize(t.num_edges());
    edge_stamp.resize(t.num_edges(), 0);
  }
  const WorldFace* Face(const PosedObject& at_proxy, FaceId f) {
    if (face_stamp[f] != stamp) {
      face_stamp[f] = stamp;
      face_ok[f] = PlaceFace(at_proxy, f, faces[f]);
    }
    return face_ok[f] ? &faces[f] : nullptr;
  }
  const WorldEdge& Edge(const PosedObject& at_proxy, EdgeId e) {
    if (edge_stamp[e] != stamp) {
      edge_stamp[e] = stamp;
      edges[e] = PlaceEdge(at_proxy, e);
    }
    return edges[e];
  }
};

// The planes of `pairs` at `proxy` into `candidates`: the tests of a pair
// at the proxy's pose, without margin.
void PairPlanes(const HapticObject& t, const Isometry3d& X_WP, const LocalModelPairs& pairs,
                double radius_m, double behind_m, std::vector<ConstraintPlane>& candidates) {
  const PosedObject at_proxy{&t, nullptr, X_WP};
  PlacedById& placed = Scratch<PlacedById>();
  placed.Begin(t);
  Vector3d foot;
  double gap;
  for (const LocalModelPairs::VertexFace& pair : pairs.vertex_faces) {
    const Vector3d v = X_WP * t.position(pair.tool_vertex);
    if (!FootOnFace(pair.face, v, behind_m, radius_m, 0, foot, gap)) continue;
    ConstraintPlane& plane = candidates.emplace_back(pairs.materials[pair.material]);
    plane.normal_W = pair.face.n;
    plane.gap_m = std::max(gap, 0.0);
    plane.point_W = foot;
    plane.tool_point_W = v;
  }
  for (const LocalModelPairs::FaceVertex& pair : pairs.face_vertices) {
    const WorldFace* tool_face = placed.Face(at_proxy, pair.tool_face);
    if (tool_face == nullptr ||
        !FootOnFace(*tool_face, pair.vertex_W, behind_m, radius_m, 0, foot, gap)) {
      continue;
    }
    ConstraintPlane& plane = candidates.emplace_back(pairs.materials[pair.material]);
    plane.normal_W = -tool_face->n;
    plane.gap_m = std::max(gap, 0.0);
    plane.point_W = pair.vertex_W;
    plane.tool_point_W = foot;
  }
  for (const LocalModelPairs::EdgeEdge& pair : pairs.edge_edges) {
    ConstraintPlane plane = pairs.materials[pair.material];
    if (!EdgePairPlane(placed.Edge(at_proxy, pair.tool_edge), pair.edge, plane)) continue;
    if (plane.gap_m < -behind_m || plane.gap_m > radius_m) continue;
    plane.gap_m = std::max(plane.gap_m, 0.0);
    candidates.push_back(plane);
  }
}

// BuildLocalModel's pairs, kept between calls (common/core/scratch.h).
struct FreshPairs {
  LocalModelPairs pairs;
};

}  // namespace

double LocalModelPairs::Moved(const Isometry3d& X_WP_now) const {
  const double turn = Eigen::AngleAxisd(X_WP.linear().transpose() * X_WP_now.linear()).angle();
  return (X_WP_now.translation() - X_WP.translation()).norm() + lever_m * turn;
}

void GatherLocalModelPairs(const PosedObject& tool, const Isometry3d& X_WP,
                           std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                           const LocalModelOptions& options, double margin_m,
                           LocalModelPairs& pairs) {
  const HapticObject& t = *tool.object;
  const double behind = Behind(t);
  // How far a pair's features may be apart now and still meet the tests
  // after a move of at most the margin.
  const double within = options.radius_m + margin_m;
  Vector3d foot;
  double gap;
  pairs.X_WP = X_WP;
  pairs.margin_m = margin_m;
  // Every point of the tool is within Reach of its origin, and the objects'
  // features the pairs hold within `within` of the tool's box: each
  // coordinate within Reach + within of the origin.
  pairs.lever_m = std::sqrt(3.0) * (Reach(t) + within);
  pairs.obstacle_count = obstacles.size();
  pairs.materials.clear();
  pairs.vertex_faces.clear();
  pairs.face_vertices.clear();
  pairs.edge_edges.clear();
  PlacedTool& placed = Scratch<PlacedTool>();
  const PosedObject at_proxy{tool.object, tool.model, X_WP};
  const AlignedBox3d near = GrowBox(WorldBox(t, X_WP), within);
  NearFeatures& object_near = Scratch<ObjectNear>().features;
  NearFeatures& tool_near = Scratch<ToolNear>().features;
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PosedObject& o = obstacles[k];
    // The object's features near the tool, and the tool's near those: on
    // both sides only what may come within the radius after the margin.
    const AlignedBox3d object_box = FindNearFeatures(o, near, object_near);
    if (object_box.isEmpty()) continue;
    FindNearFeatures(at_proxy, GrowBox(object_box, within), tool_near);
    PlaceTool(t, X_WP, tool_near, placed);
    for (const FaceId f : object_near.faces) {  // tool vertex, object face
      WorldFace face;
      if (!PlaceFace(o, f, face)) continue;
      int material = -1;
      for (size_t i = 0; i < placed.vertices.size(); ++i) {
        if (!FootOnFace(face, placed.vertices[i], behind + margin_m, within, margin_m, foot, gap)) {
          continue;
        }
        pairs.vertex_faces.push_back(
            {tool_near.vertices[i], face, MaterialIndex(*o.object, f, ids[k], pairs, material)});
      }
    }
    // Features beyond the box are farther than the radius and the margin
    // from the tool: a move the pairs hold for cannot bring them together.
    for (const VertexId v : object_near.vertices) {  // object vertex, tool face
      const Vector3d q = o.X_WO * o.object->position(v);
      if (!near.contains(q)) continue;
      int material = -1;
      for (size_t i = 0; i < placed.faces.size(); ++i) {
        if (!FootOnFace(placed.faces[i], q, behind + margin_m, within, margin_m, foot, gap)) {
          continue;
        }
        pairs.face_vertices.push_back(
            {placed.face_ids[i], q,
             MaterialIndex(*o.object, o.object->VertexFaces(v).front(), ids[k], pairs, material)});
      }
    }
    for (const EdgeId e : object_near.edges) {  // object edge, tool edge
      const WorldEdge edge = PlaceEdge(o, e);
      AlignedBox3d box(edge.from);
      box.extend(edge.to);
      if (!box.intersects(near)) continue;
      int material = -1;
      for (size_t i = 0; i < placed.edges.size(); ++i) {
        const WorldEdge& g = placed.edges[i];
        if (!EdgePairMayGivePlane(g, edge, margin_m, margin_m / pairs.lever_m, options.radius_m,
                                  behind)) {
          continue;
        }
        pairs.edge_edges.push_back(
            {tool_near.edges[i], edge,
             MaterialIndex(*o.object, o.object->EdgeFaces(e).front(), ids[k], pairs, material)});
      }
    }
  }
}

void ModelFromPairs(const HapticObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                    const LocalModelPairs& pairs, const LocalModelOptions& options,
                    LocalModel& model) {
  model.X_WP = proxy.X_WP;
  model.p_WD = p_WD;
  model.validity_radius_m = options.radius_m;
  model.force_clamp_n = options.force_clamp_n;
  model.friction = options.friction;
  model.touching = proxy.touching;
  model.touch_point_W = proxy.touching ? proxy.p_WC : proxy.X_WP.translation();
  model.planes.clear();
  const double size = tool.bounding_box().diagonal().norm();
  std::vector<ConstraintPlane>& candidates = Scratch<CandidatePlanes>().planes;
  candidates.clear();
  PairPlanes(tool, proxy.X_WP, pairs, options.radius_m, Behind(tool), candidates);
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

void BuildLocalModel(const PosedObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                     std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                     const LocalModelOptions& options, LocalModel& model) {
  LocalModelPairs& pairs = Scratch<FreshPairs>().pairs;
  GatherLocalModelPairs(tool, proxy.X_WP, obstacles, ids, options, 0, pairs);
  ModelFromPairs(*tool.object, proxy, p_WD, pairs, options, model);
}

}  // namespace hs
