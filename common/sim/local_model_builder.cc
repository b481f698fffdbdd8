#include "common/sim/local_model_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/collision/faces_in_box.h"
#include "common/core/scratch.h"
#include "common/sim/edge_pairs_batch.h"
#include "common/sim/motion_bounds.h"

namespace hs {
namespace {

// Kept between steps (common/core/scratch.h): the tool's features near
// an object at the proxy pose, and the candidate planes of a model.
struct PlacedTool {
  std::vector<Vector3d> vertices;
  std::vector<WorldFace> faces;
  std::vector<FaceId> face_ids;
  std::vector<WorldEdge> edges;
  std::vector<EdgeLengths> edge_lengths;
};
struct CandidatePlanes {
  std::vector<ConstraintPlane> planes;
  std::vector<int> order;
};

// Two planes closer than these in direction (cosine) and offset (relative
// to the tool's size) are one: the two triangles of a flat face.
constexpr double kSameNormalCos = 1 - 1e-9;
constexpr double kSameOffset = 1e-9;

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

// Marks on an object's elements (faces, vertices or edges) that tell this
// use's from older ones: `stamp` is this use's.
struct Marks {
  std::vector<uint32_t> marks;
  uint32_t stamp = 0;

  void Begin(int count) {
    if (++stamp == 0) {  // wrapped: forget every mark
      std::fill(marks.begin(), marks.end(), 0);
      stamp = 1;
    }
    if (static_cast<int>(marks.size()) < count) marks.resize(count, 0);
  }
  // Whether `i` is marked in this use.
  bool Marked(int i) const { return marks[i] == stamp; }
  // True the first time `i` is marked in this use.
  bool Mark(int i) {
    if (marks[i] == stamp) return false;
    marks[i] = stamp;
    return true;
  }
};

// An object at one pose: its vertices' world positions and its faces'
// unit normals, each computed once however many faces and edges share it.
class PlacedObject {
 public:
  void Begin(const PosedObject& o) {
    o_ = o;
    const HapticObject& h = *o.object;
    placed_vertices_.Begin(h.num_vertices());
    if (static_cast<int>(vertices_.size()) < h.num_vertices()) vertices_.resize(h.num_vertices());
    placed_normals_.Begin(h.num_faces());
    if (static_cast<int>(normals_.size()) < h.num_faces()) normals_.resize(h.num_faces());
  }
  const PosedObject& posed() const { return o_; }

  const Vector3d& Vertex(VertexId v) {
    if (placed_vertices_.Mark(v)) vertices_[v] = o_.X_WO * o_.object->position(v);
    return vertices_[v];
  }
  // Face `f` in the world frame; false when it has no area.
  bool PlaceFace(FaceId f, WorldFace& out) {
    const Face& face = o_.object->face(f);
    out.a = Vertex(face.vertices[0]);
    out.b = Vertex(face.vertices[1]);
    out.c = Vertex(face.vertices[2]);
    const Vector3d normal = (out.b - out.a).cross(out.c - out.a);
    const bool has_area = normal.norm() > 0;
    if (has_area) out.n = normal.normalized();
    if (placed_normals_.Mark(f)) normals_[f] = has_area ? out.n : Vector3d::Zero();
    return has_area;
  }
  // The unit normal of face `f` (zero when it has no area).
  const Vector3d& Normal(FaceId f) {
    if (!placed_normals_.Marked(f)) {
      WorldFace face;
      (void)PlaceFace(f, face);  // records the normal
    }
    return normals_[f];
  }
  // Edge `e` in the world frame.
  WorldEdge PlaceEdge(EdgeId e) {
    const Edge& edge = o_.object->edge(e);
    WorldEdge out{Vertex(edge.vertices[0]), Vertex(edge.vertices[1]), Vector3d::Zero()};
    for (const FaceId f : o_.object->EdgeFaces(e)) out.out += Normal(f);
    return out;
  }

 private:
  PosedObject o_;
  std::vector<Vector3d> vertices_, normals_;
  Marks placed_vertices_, placed_normals_;
};

// An object's faces near a region, their vertices and edges (each once),
// and the object placed at its pose.
struct NearFeatures {
  std::vector<FaceId> faces;
  std::vector<VertexId> vertices;
  std::vector<EdgeId> edges;
  Marks vertex_marks, edge_marks;
  PlacedObject placed;
};
struct ObjectNear {
  NearFeatures features;
};
struct ToolNear {
  NearFeatures features;
};

// The faces of the object `out` is placed for whose volumes meet `box_W`,
// and their vertices and edges, each once (in the order the hierarchy
// gives them: the model does not depend on the order of the pairs).
// Returns the world box of those faces.
AlignedBox3d FindNearFeatures(const AlignedBox3d& box_W, NearFeatures& out) {
  const PosedObject& o = out.placed.posed();
  out.faces.clear();
  out.vertices.clear();
  out.edges.clear();
  FindFacesInBox(*o.model, o.X_WO, box_W, out.faces);
  out.vertex_marks.Begin(o.object->num_vertices());
  out.edge_marks.Begin(o.object->num_edges());
  for (const FaceId f : out.faces) {
    const Face& face = o.object->face(f);
    for (const VertexId v : face.vertices) {
      if (out.vertex_marks.Mark(v)) out.vertices.push_back(v);
    }
    for (const EdgeId e : face.edges) {
      if (out.edge_marks.Mark(e)) out.edges.push_back(e);
    }
  }
  AlignedBox3d box;
  for (const VertexId v : out.vertices) box.extend(out.placed.Vertex(v));
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

// The tool's `near` features in the world frame, at the pose it is placed
// at.
void PlaceTool(NearFeatures& near, PlacedTool& placed) {
  placed.vertices.clear();
  for (const VertexId v : near.vertices) placed.vertices.push_back(near.placed.Vertex(v));
  placed.faces.clear();
  placed.face_ids.clear();
  for (const FaceId g : near.faces) {
    WorldFace face;
    if (!near.placed.PlaceFace(g, face)) continue;
    placed.faces.push_back(face);
    placed.face_ids.push_back(g);
  }
  placed.edges.clear();
  placed.edge_lengths.clear();
  for (const EdgeId e : near.edges) {
    placed.edges.push_back(near.placed.PlaceEdge(e));
    placed.edge_lengths.push_back(LengthsOf(placed.edges.back()));
  }
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

// Which of a set of boxes (world frame) may meet a query box: a uniform
// grid of cells, each listing the boxes that meet it, kept between
// searches (common/core/scratch.h) so that it stops allocating. For a few
// queries the grid costs more to build than it saves: each query then
// tests every box.
class BoxGrid {
 public:
  // Bins `boxes` (kept by reference until the next Build) in cells of side
  // `cell_m` at least, no more cells than a few per box, for `queries`
  // queries to come.
  void Build(const std::vector<AlignedBox3d>& boxes, double cell_m, size_t queries) {
    boxes_ = &boxes;
    // Binning a box costs about as much as testing it against a few
    // dozen queries (step_bench's remote_device, 2026-11-30).
    every_box_ = queries <= kEveryBoxQueries;
    if (every_box_) return;
    AlignedBox3d bounds;
    for (const AlignedBox3d& box : boxes) {
      if (!box.isEmpty()) bounds.extend(box);
    }
    seen_.assign(boxes.size(), 0);
    stamp_ = 0;
    start_.clear();
    items_.clear();
    if (bounds.isEmpty()) return;
    origin_ = bounds.min();
    const Vector3d sizes = bounds.sizes();
    const double max_cells = std::clamp(4.0 * static_cast<double>(boxes.size()), 64.0, 16384.0);
    double cell = std::max(cell_m, 1e-12);
    for (;;) {
      double cells = 1;
      for (int i = 0; i < 3; ++i) {
        n_[i] = static_cast<int>(std::min(std::floor(sizes[i] / cell), 1e6)) + 1;
        cells *= n_[i];
      }
      if (cells <= max_cells) break;
      cell *= std::cbrt(cells / max_cells) * 1.01;
    }
    inv_cell_ = 1 / cell;
    start_.assign(static_cast<size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    // Count, then place: start_[c] .. start_[c + 1] are cell c's boxes.
    for (int pass = 0; pass < 2; ++pass) {
      for (size_t k = 0; k < boxes.size(); ++k) {
        int lo[3], hi[3];
        if (!Cells(boxes[k], lo, hi)) continue;
        for (int z = lo[2]; z <= hi[2]; ++z) {
          for (int y = lo[1]; y <= hi[1]; ++y) {
            for (int x = lo[0]; x <= hi[0]; ++x) {
              const int c = Cell(x, y, z);
              if (pass == 0) {
                ++start_[c + 1];
              } else {
                items_[fill_[c]++] = static_cast<int>(k);
              }
            }
          }
        }
      }
      if (pass == 0) {
        for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
        items_.resize(start_.back());
        fill_.assign(start_.begin(), start_.end() - 1);
      }
    }
  }

  // Calls visit(k) once for each box k that meets `query`, in no
  // particular order.
  template <typename Visit>
  void ForEachMeeting(const AlignedBox3d& query, Visit&& visit) {
    if (every_box_) {
      for (size_t k = 0; k < boxes_->size(); ++k) {
        if ((*boxes_)[k].intersects(query)) visit(static_cast<int>(k));
      }
      return;
    }
    int lo[3], hi[3];
    if (start_.empty() || !Cells(query, lo, hi)) return;
    if (++stamp_ == 0) {  // wrapped: forget every mark
      std::fill(seen_.begin(), seen_.end(), 0);
      stamp_ = 1;
    }
    const std::vector<AlignedBox3d>& boxes = *boxes_;
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const int c = Cell(x, y, z);
          for (int i = start_[c]; i < start_[c + 1]; ++i) {
            const int k = items_[i];
            if (seen_[k] == stamp_) continue;
            seen_[k] = stamp_;
            if (boxes[k].intersects(query)) visit(k);
          }
        }
      }
    }
  }

 private:
  int Cell(int x, int y, int z) const { return (z * n_[1] + y) * n_[0] + x; }
  // The range of cells `box` meets, clamped to the grid; false when it
  // misses the grid or is empty.
  bool Cells(const AlignedBox3d& box, int lo[3], int hi[3]) const {
    if (box.isEmpty()) return false;
    for (int i = 0; i < 3; ++i) {
      const double from = (box.min()[i] - origin_[i]) * inv_cell_;
      const double to = (box.max()[i] - origin_[i]) * inv_cell_;
      if (!(to >= 0 && from < n_[i])) return false;
      lo[i] = from <= 0 ? 0 : static_cast<int>(from);
      hi[i] = to >= n_[i] - 1 ? n_[i] - 1 : static_cast<int>(to);
    }
    return true;
  }

  static constexpr size_t kEveryBoxQueries = 24;
  const std::vector<AlignedBox3d>* boxes_ = nullptr;
  bool every_box_ = false;
  Vector3d origin_ = Vector3d::Zero();
  double inv_cell_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<int> start_, items_, fill_;
  std::vector<uint32_t> seen_;
  uint32_t stamp_ = 0;
};

// The box of every point p with FootOnFace(face, p, below_m, above_m,
// margin_m) true (`pad_m` more for rounding): the face grown by the margin
// in its plane (its edges pushed out by margin_m and FootOnFace's slack:
// the triangle scaled about its incentre), swept from below_m behind to
// above_m in front.
AlignedBox3d FootBox(const WorldFace& face, double below_m, double above_m, double margin_m,
                     double pad_m) {
  const double la = (face.c - face.b).norm(), lb = (face.a - face.c).norm(),
               lc = (face.b - face.a).norm();
  const double perimeter = la + lb + lc;
  const double inradius = (face.b - face.a).cross(face.c - face.a).norm() / perimeter;
  const double out_m = margin_m + 1e-9 * std::max({la, lb, lc});
  AlignedBox3d box;
  if (!(inradius > 1e-9 * perimeter)) {  // a sliver: anywhere
    box.extend(Vector3d::Constant(-std::numeric_limits<double>::infinity()));
    box.extend(Vector3d::Constant(std::numeric_limits<double>::infinity()));
    return box;
  }
  const Vector3d centre = (la * face.a + lb * face.b + lc * face.c) / perimeter;
  const double scale = (inradius + out_m) / inradius;
  for (const Vector3d* corner : {&face.a, &face.b, &face.c}) {
    const Vector3d grown = centre + scale * (*corner - centre);
    box.extend(grown + above_m * face.n);
    box.extend(grown - below_m * face.n);
  }
  return GrowBox(box, pad_m);
}

// A segment's box.
AlignedBox3d SegmentBox(const Vector3d& from, const Vector3d& to) {
  AlignedBox3d box(from);
  box.extend(to);
  return box;
}

// One object's features of one kind near the tool, for a search: placed
// in the world frame, their ids, the boxes the grid bins them by, and the
// index of their material plane in the pairs (-1: none yet).
struct ObjectSide {
  std::vector<WorldFace> faces;
  std::vector<FaceId> face_ids;
  std::vector<Vector3d> points;
  std::vector<VertexId> point_ids;
  std::vector<WorldEdge> edges;
  std::vector<EdgeLengths> edge_lengths;
  std::vector<EdgeId> edge_ids;
  EdgeColumns edge_columns;  // `edges` again, for the batched test
  double longest_m = 0;      // the longest of `edges`
  std::vector<AlignedBox3d> boxes;
  std::vector<int> material;
  BoxGrid grid;
  std::vector<int> meeting, kept;  // a query's boxes, and those kept

  void Clear() {
    faces.clear();
    face_ids.clear();
    points.clear();
    point_ids.clear();
    edges.clear();
    edge_lengths.clear();
    edge_ids.clear();
    edge_columns.Clear();
    longest_m = 0;
    boxes.clear();
  }
};

// What rounding may move a bound of the pairs near proxy pose X_WP by,
// metres: far more than a double's rounding of coordinates that size.
double BoundSlack(const Isometry3d& X_WP, double lever_m) {
  return 1e-9 * (1 + X_WP.translation().cwiseAbs().maxCoeff() + lever_m);
}

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
// many pairs name it (Marks tell this placing's entries from older ones).
struct PlacedById {
  std::vector<WorldFace> faces;
  std::vector<bool> face_ok;
  std::vector<WorldEdge> edges;
  Marks placed_faces, placed_edges;
  PlacedObject tool;

  void Begin(const PosedObject& at_proxy) {
    const HapticObject& t = *at_proxy.object;
    placed_faces.Begin(t.num_faces());
    faces.resize(t.num_faces());
    face_ok.resize(t.num_faces());
    placed_edges.Begin(t.num_edges());
    edges.resize(t.num_edges());
    tool.Begin(at_proxy);
  }
  const Vector3d& Vertex(VertexId v) { return tool.Vertex(v); }
  const WorldFace* Face(FaceId f) {
    if (placed_faces.Mark(f)) face_ok[f] = tool.PlaceFace(f, faces[f]);
    return face_ok[f] ? &faces[f] : nullptr;
  }
  const WorldEdge& Edge(EdgeId e) {
    if (placed_edges.Mark(e)) edges[e] = tool.PlaceEdge(e);
    return edges[e];
  }
};

// The planes of the pairs of `pairs` whose floor is in (from_m, to_m], with
// the tool `placed` at the proxy, appended to `candidates`: the tests of a
// pair at the proxy's pose, without margin.
void PairPlanes(const LocalModelPairs& pairs, double radius_m, double behind_m, double from_m,
                double to_m, PlacedById& placed, std::vector<ConstraintPlane>& candidates) {
  auto in_window = [&](double floor_m) { return floor_m > from_m && floor_m <= to_m; };
  Vector3d foot;
  double gap;
  for (const LocalModelPairs::VertexFace& pair : pairs.vertex_faces) {
    if (!in_window(pair.floor_m)) continue;
    const Vector3d& v = placed.Vertex(pair.tool_vertex);
    if (!FootOnFace(pair.face, v, behind_m, radius_m, 0, foot, gap)) continue;
    ConstraintPlane& plane = candidates.emplace_back(pairs.materials[pair.material]);
    plane.normal_W = pair.face.n;
    plane.gap_m = std::max(gap, 0.0);
    plane.point_W = foot;
    plane.tool_point_W = v;
  }
  for (const LocalModelPairs::FaceVertex& pair : pairs.face_vertices) {
    if (!in_window(pair.floor_m)) continue;
    const WorldFace* tool_face = placed.Face(pair.tool_face);
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
    if (!in_window(pair.floor_m)) continue;
    ConstraintPlane plane = pairs.materials[pair.material];
    if (!EdgePairPlane(placed.Edge(pair.tool_edge), pair.edge, plane)) continue;
    if (plane.gap_m < -behind_m || plane.gap_m > radius_m) continue;
    plane.gap_m = std::max(plane.gap_m, 0.0);
    candidates.push_back(plane);
  }
}

// The nearest distinct planes of `candidates`, at most `max_planes`, into
// `planes`: the candidates in Nearer's order (a total one), each kept
// unless one kept is the same plane. Sorts indices, the nearest few first
// (`order` is scratch).
void NearestDistinct(const std::vector<ConstraintPlane>& candidates, int max_planes, double size,
                     std::vector<int>& order, std::vector<ConstraintPlane>& planes) {
  auto nearer = [&](int x, int y) { return NearerPlane(candidates[x], candidates[y]); };
  order.resize(candidates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  // Most models take their planes from the nearest few candidates.
  size_t sorted = std::min(order.size(), static_cast<size_t>(4 * std::max(max_planes, 1)));
  std::partial_sort(order.begin(), order.begin() + sorted, order.end(), nearer);
  for (;;) {
    planes.clear();
    for (size_t i = 0; i < sorted; ++i) {
      if (static_cast<int>(planes.size()) == max_planes) return;
      const ConstraintPlane& plane = candidates[order[i]];
      const bool seen = std::any_of(planes.begin(), planes.end(), [&](const ConstraintPlane& p) {
        return SamePlane(p, plane, size);
      });
      if (!seen) planes.push_back(plane);
    }
    if (sorted == order.size()) return;
    std::sort(order.begin() + sorted, order.end(), nearer);  // after the first `sorted`
    sorted = order.size();
  }
}

// BuildLocalModel's pairs, kept between calls (common/core/scratch.h).
struct FreshPairs {
  LocalModelPairs pairs;
};

}  // namespace

double MovedBy(const Isometry3d& from, const Isometry3d& to, double lever_m) {
  const double turn = Eigen::AngleAxisd(from.linear().transpose() * to.linear()).angle();
  return (to.translation() - from.translation()).norm() + lever_m * turn;
}

bool NearerPlane(const ConstraintPlane& x, const ConstraintPlane& y) {
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
  if (x.object != y.object) return x.object < y.object;
  // Two faces' pairs may give one plane with different materials: the
  // order of the pairs must not choose between them.
  if (x.stiffness_n_per_m != y.stiffness_n_per_m) {
    return x.stiffness_n_per_m < y.stiffness_n_per_m;
  }
  if (x.damping_ns_per_m != y.damping_ns_per_m) return x.damping_ns_per_m < y.damping_ns_per_m;
  if (x.static_friction != y.static_friction) return x.static_friction < y.static_friction;
  return x.dynamic_friction < y.dynamic_friction;
}

void SetModelProxy(const ProxyState& proxy, const Vector3d& p_WD, LocalModel& model) {
  model.X_WP = proxy.X_WP;
  model.p_WD = p_WD;
  model.touching = proxy.touching;
  model.touch_point_W = proxy.touching ? proxy.p_WC : proxy.X_WP.translation();
}

double PlaneTouchTolerance(const HapticObject& tool) {
  return 1e-6 * tool.bounding_box().diagonal().norm();
}

double LocalModelPairs::Moved(const Isometry3d& X_WP_now) const {
  if (moves == ProxyMoves::kShiftsOnly && X_WP_now.linear() != X_WP.linear()) {
    return std::numeric_limits<double>::infinity();
  }
  return MovedBy(X_WP, X_WP_now, lever_m);
}

void GatherLocalModelPairs(const PosedObject& tool, const Isometry3d& X_WP,
                           std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                           const LocalModelOptions& options, double margin_m,
                           LocalModelPairs& pairs) {
  GatherLocalModelPairs(tool, X_WP, obstacles, ids, options, margin_m, options.radius_m,
                        ProxyMoves::kAny, pairs);
}

void GatherLocalModelPairs(const PosedObject& tool, const Isometry3d& X_WP,
                           std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                           const LocalModelOptions& options, double margin_m, double reach_m,
                           ProxyMoves moves, LocalModelPairs& pairs) {
  const HapticObject& t = *tool.object;
  const double behind = PlaneTouchTolerance(t);
  // The gap the pairs are gathered for: the radius, or less.
  const double radius_m = std::min(reach_m, options.radius_m);
  // How far a pair's features may be apart now and still meet the tests
  // after a move of at most the margin.
  const double within = radius_m + margin_m;
  Vector3d foot;
  double gap;
  pairs.X_WP = X_WP;
  pairs.margin_m = margin_m;
  pairs.moves = moves;
  // Every point of the tool is within Reach of its origin, and the objects'
  // features the pairs hold within `within` of the tool's box: each
  // coordinate within Reach + within of the origin.
  pairs.lever_m = std::sqrt(3.0) * (Reach(t) + within);
  // The most the tool may turn while its features move by the margin.
  const double turn = moves == ProxyMoves::kAny ? margin_m / pairs.lever_m : 0.0;
  pairs.obstacle_count = obstacles.size();
  pairs.materials.clear();
  pairs.vertex_faces.clear();
  pairs.face_vertices.clear();
  pairs.edge_edges.clear();
  PlacedTool& placed = Scratch<PlacedTool>();
  ObjectSide& side = Scratch<ObjectSide>();
  const PosedObject at_proxy{tool.object, tool.model, X_WP};
  const AlignedBox3d near = GrowBox(WorldBox(t, X_WP), within);
  NearFeatures& object_near = Scratch<ObjectNear>().features;
  NearFeatures& tool_near = Scratch<ToolNear>().features;
  // Rounding allowance on the boxes the grids compare.
  const double pad = BoundSlack(X_WP, pairs.lever_m);
  // Edge pairs farther apart than move.segments_m cannot give a plane after
  // a move of at most the margin (EdgePairMayGivePlane).
  const EdgeMove move(margin_m, turn, radius_m, behind);
  // The tests are loosened for rounding (FootOnFace's slack, the edges'
  // ends): a short search holds the planes nearer than its reach by more.
  pairs.complete_m =
      radius_m < options.radius_m ? radius_m - pad : std::numeric_limits<double>::infinity();
  tool_near.placed.Begin(at_proxy);
  for (size_t k = 0; k < obstacles.size(); ++k) {
    const PosedObject& o = obstacles[k];
    // The object's features near the tool, and the tool's near those: on
    // both sides only what may come within the radius after the margin.
    PlacedObject& object = object_near.placed;
    object.Begin(o);
    const AlignedBox3d object_box = FindNearFeatures(near, object_near);
    if (object_box.isEmpty()) continue;
    FindNearFeatures(GrowBox(object_box, within), tool_near);
    PlaceTool(tool_near, placed);
    // Each kind of pair: the object's features binned in a grid by where
    // their partner must be, each of the tool's looked up in it, and the
    // pair's tests run on what the grid gives.
    AlignedBox3d tool_vertices;
    for (const Vector3d& v : placed.vertices) tool_vertices.extend(v);
    side.Clear();
    for (const FaceId f : object_near.faces) {  // tool vertex, object face
      WorldFace face;
      if (!object.PlaceFace(f, face)) continue;
      side.faces.push_back(face);
      side.face_ids.push_back(f);
      side.boxes.push_back(
          FootBox(face, behind + margin_m, within, margin_m, pad).intersection(tool_vertices));
    }
    side.material.assign(side.faces.size(), -1);
    side.grid.Build(side.boxes, within, placed.vertices.size());
    for (size_t i = 0; i < placed.vertices.size(); ++i) {
      const Vector3d& v = placed.vertices[i];
      side.grid.ForEachMeeting(AlignedBox3d(v, v), [&](int j) {
        if (!FootOnFace(side.faces[j], v, behind + margin_m, within, margin_m, foot, gap)) return;
        pairs.vertex_faces.push_back(
            {tool_near.vertices[i], side.faces[j],
             MaterialIndex(*o.object, side.face_ids[j], ids[k], pairs, side.material[j]), gap});
      });
    }
    // Features beyond the box are farther than the radius and the margin
    // from the tool: a move the pairs hold for cannot bring them together.
    side.Clear();
    for (const VertexId v : object_near.vertices) {  // object vertex, tool face
      const Vector3d& q = object.Vertex(v);
      if (!near.contains(q)) continue;
      side.points.push_back(q);
      side.point_ids.push_back(v);
      side.boxes.emplace_back(q, q);
    }
    side.material.assign(side.points.size(), -1);
    side.grid.Build(side.boxes, within, placed.faces.size());
    for (size_t i = 0; i < placed.faces.size(); ++i) {
      const WorldFace& face = placed.faces[i];
      side.grid.ForEachMeeting(FootBox(face, behind + margin_m, within, margin_m, pad), [&](int j) {
        const Vector3d& q = side.points[j];
        if (!FootOnFace(face, q, behind + margin_m, within, margin_m, foot, gap)) return;
        const VertexId v = side.point_ids[j];
        pairs.face_vertices.push_back({placed.face_ids[i], q,
                                       MaterialIndex(*o.object, o.object->VertexFaces(v).front(),
                                                     ids[k], pairs, side.material[j]),
                                       gap});
      });
    }
    side.Clear();
    for (const EdgeId e : object_near.edges) {  // object edge, tool edge
      const Edge& ends = o.object->edge(e);
      const AlignedBox3d box =
          SegmentBox(object.Vertex(ends.vertices[0]), object.Vertex(ends.vertices[1]));
      if (!box.intersects(near)) continue;
      const WorldEdge edge = object.PlaceEdge(e);
      side.edges.push_back(edge);
      side.edge_lengths.push_back(LengthsOf(edge));
      side.edge_ids.push_back(e);
      side.edge_columns.Add(edge, side.edge_lengths.back().edge_m);
      side.boxes.push_back(box);
      side.longest_m = std::max(side.longest_m, side.edge_lengths.back().edge_m);
    }
    side.material.assign(side.edges.size(), -1);
    side.grid.Build(side.boxes, within, placed.edges.size());
    for (size_t i = 0; i < placed.edges.size(); ++i) {
      const WorldEdge& g = placed.edges[i];
      const EdgeLengths& g_lengths = placed.edge_lengths[i];
      const double reach = move.segments_m + SegmentSlack(g_lengths.edge_m, side.longest_m) + pad;
      // The object edges near enough, then those whose lines pass the first
      // tests, a batch at a time, then the rest of the tests one by one.
      side.meeting.clear();
      side.grid.ForEachMeeting(GrowBox(SegmentBox(g.from, g.to), reach),
                               [&](int j) { side.meeting.push_back(j); });
      side.kept.resize(side.meeting.size());
      const size_t passed =
          KeepEdgesWhoseLinesMayMeet(g.from, g.to - g.from, g_lengths.edge_m, side.edge_columns,
                                     side.meeting, move, side.kept.data());
      for (size_t m = 0; m < passed; ++m) {
        const int j = side.kept[m];
        const WorldEdge& edge = side.edges[j];
        const EdgeLengths& edge_lengths = side.edge_lengths[j];
        double apart_m;
        if (!EdgePairMayGivePlane(g, g_lengths, edge, edge_lengths, move, apart_m)) continue;
        const EdgeId e = side.edge_ids[j];
        pairs.edge_edges.push_back(
            {tool_near.edges[i], edge,
             MaterialIndex(*o.object, o.object->EdgeFaces(e).front(), ids[k], pairs,
                           side.material[j]),
             apart_m - SegmentSlack(g_lengths.edge_m, edge_lengths.edge_m) - behind});
      }
    }
  }
}

void SetModelState(const ProxyState& proxy, const Vector3d& p_WD, const LocalModelOptions& options,
                   LocalModel& model) {
  SetModelProxy(proxy, p_WD, model);
  model.validity_radius_m = options.radius_m;
  model.force_clamp_n = options.force_clamp_n;
  model.friction = options.friction;
}

bool ModelFromPairs(const HapticObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                    const LocalModelPairs& pairs, const LocalModelOptions& options,
                    LocalModel& model) {
  SetModelState(proxy, p_WD, options, model);
  const double size = tool.bounding_box().diagonal().norm();
  const double behind = PlaneTouchTolerance(tool);
  CandidatePlanes& candidate_planes = Scratch<CandidatePlanes>();
  std::vector<ConstraintPlane>& candidates = candidate_planes.planes;
  candidates.clear();
  PlacedById& placed = Scratch<PlacedById>();
  placed.Begin(PosedObject{&tool, nullptr, proxy.X_WP});
  // A pair's plane is at least its floor less `moved` away (the pairs'
  // floor_m), and a pair not gathered gives none nearer than complete_m:
  // the pairs are taken in rising bands of floor until the nearest
  // max_planes distinct planes of those taken are all nearer than any
  // plane left could be, or none left could give a plane at all. Every
  // plane left out then sorts after the last one kept: the model is the
  // one all the pairs make.
  const double moved = pairs.Moved(proxy.X_WP) + BoundSlack(proxy.X_WP, pairs.lever_m);
  if (!std::isfinite(moved)) return false;  // turned, from pairs for shifts alone
  const double band = options.radius_m / 8;
  double from = -std::numeric_limits<double>::infinity();
  double to = moved + band;
  for (;;) {
    PairPlanes(pairs, options.radius_m, behind, from, to, placed, candidates);
    NearestDistinct(candidates, options.max_planes, size, candidate_planes.order, model.planes);
    // Every plane nearer than this has been taken.
    const double taken = std::min(to - moved, pairs.complete_m);
    if (static_cast<int>(model.planes.size()) >= options.max_planes &&
        (model.planes.empty() || model.planes.back().gap_m < taken)) {
      return true;
    }
    if (taken >= options.radius_m) return true;
    if (to - moved >= pairs.complete_m) return false;
    from = to;
    // A model not yet full takes every pair left that may count: most
    // such models are the few planes of a coarse object.
    to = static_cast<int>(model.planes.size()) < options.max_planes
             ? moved + std::min(options.radius_m, pairs.complete_m) + band
             : to + 2 * (to - moved);
  }
}

void BuildLocalModel(const PosedObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                     std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                     const LocalModelOptions& options, LocalModel& model) {
  LocalModelPairs& pairs = Scratch<FreshPairs>().pairs;
  GatherLocalModelPairs(tool, proxy.X_WP, obstacles, ids, options, 0, pairs);
  (void)ModelFromPairs(*tool.object, proxy, p_WD, pairs, options, model);  // the whole radius
}

}  // namespace hs
