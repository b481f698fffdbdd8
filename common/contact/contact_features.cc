#include "common/contact/contact_features.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <tuple>

#include "absl/container/flat_hash_set.h"

#include "common/contact/closest_points.h"
#include "common/contact/placed_vertices.h"
#include "common/contact/side_contact.h"
#include "common/core/id_memo.h"
#include "common/core/scratch.h"

namespace hs {
namespace {

// One object's face in F's frame, with its ids.
struct PosedFace {
  const HapticObject* object;
  FaceId id;
  Triangle3d corners;

  VertexId vertex(int i) const { return object->face(id).vertices[i]; }
  // Edge i joins corners i and i + 1.
  EdgeId edge(int i) const { return object->face(id).edges[i]; }

  // Edge i only splits one polygon of the source model in two (the diagonal
  // of a triangulated quad): not an edge of the shape, so a contact on it is
  // a contact on the face.
  bool splits_polygon(int i) const {
    const auto faces = object->EdgeFaces(edge(i));
    return faces.size() == 2 && object->face(faces[0]).source_polygon != kNoPolygon &&
           object->face(faces[0]).source_polygon == object->face(faces[1]).source_polygon;
  }

  // Edge i as a feature: itself, or this face when it splits a polygon.
  Feature edge_feature(int i) const {
    return splits_polygon(i) ? Feature{FeatureKind::kFace, id}
                             : Feature{FeatureKind::kEdge, edge(i)};
  }
};

// Bit i set when edge i of a face (corners i and i + 1) is not beyond the
// tolerance on one side of the other face's plane, given the corners'
// signed distances `off` from it.
unsigned NearEdges(const std::array<double, 3>& off, double tol) {
  const unsigned above0 = off[0] > tol, above1 = off[1] > tol, above2 = off[2] > tol;
  const unsigned below0 = off[0] < -tol, below1 = off[1] < -tol, below2 = off[2] < -tol;
  const unsigned beyond = ((above0 & above1) | (below0 & below1)) |
                          ((above1 & above2) | (below1 & below2)) << 1 |
                          ((above2 & above0) | (below2 & below0)) << 2;
  return ~beyond & 7u;
}

// A face's edges, each with its vector and box (edge i joins corners i and
// i + 1).
struct FaceEdges {
  explicit FaceEdges(const Triangle3d& corners) {
    for (int i = 0; i < 3; ++i) {
      const Vector3d &p = corners[i], &q = corners[(i + 1) % 3];
      along[i] = q - p;
      for (int d = 0; d < 3; ++d) {
        lo[i][d] = std::min(p[d], q[d]);
        hi[i][d] = std::max(p[d], q[d]);
      }
    }
  }
  std::array<Vector3d, 3> along, lo, hi;
};

// A face of F's edges, with the unit vector across each in the face's
// plane (zero for a degenerate face or edge).
struct FixedFaceEdges {
  FixedFaceEdges(const Triangle3d& corners, const Vector3d& unit_normal) : edges(corners) {
    for (int i = 0; i < 3; ++i) {
      const Vector3d a = unit_normal.cross(edges.along[i]);
      across[i] = a.squaredNorm() > 0 ? a.normalized() : Vector3d::Zero();
    }
  }
  FaceEdges edges;
  std::array<Vector3d, 3> across;
};

// Whether boxes [lo1, hi1] and [lo2, hi2] are more than `tol` apart along
// some axis.
bool BoxesApart(const Vector3d& lo1, const Vector3d& hi1, const Vector3d& lo2, const Vector3d& hi2,
                double tol) {
  for (int d = 0; d < 3; ++d) {
    if (hi1[d] + tol < lo2[d] || hi2[d] + tol < lo1[d]) return true;
  }
  return false;
}

// Whether the corners of a face lie more than 2 `tol` (the slack of the
// lines' test in AddPair) on one side of the plane through an edge starting
// at `start`, perpendicular to its face, whose unit normal is `across`:
// then no point of the face is within `tol` of the edge.
bool BesideEdge(const Triangle3d& corners, const Vector3d& start, const Vector3d& across,
                double tol) {
  const double d0 = across.dot(corners[0] - start), d1 = across.dot(corners[1] - start),
               d2 = across.dot(corners[2] - start);
  return std::min({d0, d1, d2}) > 2 * tol || std::max({d0, d1, d2}) < -2 * tol;
}

Vector3d UnitNormal(const Triangle3d& t) {
  const Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  return n.squaredNorm() > 0 ? n.normalized() : Vector3d::Zero();
}

// The lowest-dimensional feature of `face` within `tolerance` of point `p`
// lying on (within tolerance of) it; an edge that only splits a source
// polygon counts as the face.
Feature FeatureHolding(const PosedFace& face, const Vector3d& p, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    if ((face.corners[i] - p).norm() <= tolerance) return {FeatureKind::kVertex, face.vertex(i)};
  }
  for (int i = 0; i < 3; ++i) {
    const Vector3d q = ClosestPointOnSegment(p, face.corners[i], face.corners[(i + 1) % 3]);
    if ((q - p).norm() <= tolerance) return face.edge_feature(i);
  }
  return {FeatureKind::kFace, face.id};
}

class Locator {
 public:
  // Takes the current scratch space's storage (one locator at a time per
  // space), empty.
  Locator(const ContactContext& c, const Isometry3d& X_FM)
      : c_(c), X_FM_(X_FM), corner_slack_(CornerSlack(c, X_FM)), s_(storage()), points_(s_.points) {
    s_.Reset();
    s_.first_face[0].Reset(c.moving.num_vertices());
    s_.first_face[1].Reset(c.fixed.num_vertices());
    s_.moving_vertices.Reset(c.moving, X_FM);
    s_.normals[0].Reset(c.moving.num_faces());
    s_.normals[1].Reset(c.fixed.num_faces());
    s_.fixed_edges_at.Reset(c.fixed.num_faces());
  }
  Locator(const Locator&) = delete;
  Locator& operator=(const Locator&) = delete;

  void AddPair(const TrianglePair& pair) {
    const PosedFace m{&c_.moving, pair.a, s_.moving_vertices.Face(pair.a)};
    const PosedFace f{&c_.fixed, pair.b, c_.FixedTriangle(pair.b)};
    const double tol = c_.tolerance_m;
    // Cheap rejections first: most corners and edge pairs of a touching
    // pair are nowhere near the other triangle. Signed distances of M's
    // corners from F's plane (0 for a flat face: never off).
    const Vector3d& n_f = s_.normals[1].Get(f.id, [&] { return UnitNormal(f.corners); });
    std::array<double, 3> m_off;
    for (int i = 0; i < 3; ++i) m_off[i] = n_f.dot(m.corners[i] - f.corners[0]);
    // A corner meets the other face alike from every face around it: each
    // (corner, face) is located once.
    for (int i = 0; i < 3; ++i) {
      const Vector3d& p = m.corners[i];
      if (std::abs(m_off[i]) > tol || !s_.Locate(0, m.vertex(i), f.id)) {
        continue;
      }
      const Vector3d q = ClosestPointOnTriangle(p, f.corners[0], f.corners[1], f.corners[2]);
      if ((q - p).norm() <= tol) {
        Add(p, {FeatureKind::kVertex, m.vertex(i)}, FeatureHolding(f, q, tol), n_f, n_f);
      }
    }
    // F's side needs M's face's normal only for what is near M's face (a
    // face of F is mostly far larger): its corners within the face's box
    // grown by twice the tolerance and the rounding, and the edges left
    // below. An edge whose ends lie beyond the tolerance on one side of the
    // other face's plane is farther than it from every edge of that face
    // (bit i: edge i), and so is an edge of F whose box is apart from M's
    // face's (M's edges' boxes lie inside it) or that M's face stays
    // beside.
    Vector3d m_lo, m_hi;
    for (int d = 0; d < 3; ++d) {
      m_lo[d] = std::min({m.corners[0][d], m.corners[1][d], m.corners[2][d]});
      m_hi[d] = std::max({m.corners[0][d], m.corners[1][d], m.corners[2][d]});
    }
    unsigned f_corners = 0;
    for (int j = 0; j < 3; ++j) {
      const Vector3d& p = f.corners[j];
      const bool inside = (p.array() >= m_lo.array() - corner_slack_).all() &&
                          (p.array() <= m_hi.array() + corner_slack_).all();
      f_corners |= unsigned{inside} << j;
    }
    const unsigned m_near = NearEdges(m_off, tol);
    const FixedFaceEdges* fixed_edges = nullptr;
    unsigned f_near = 0;
    if (m_near != 0) {
      fixed_edges = &s_.FixedEdges(f.id, f.corners, n_f);
      for (int j = 0; j < 3; ++j) {
        if (!BoxesApart(m_lo, m_hi, fixed_edges->edges.lo[j], fixed_edges->edges.hi[j], tol) &&
            !BesideEdge(m.corners, f.corners[j], fixed_edges->across[j], tol)) {
          f_near |= 1u << j;
        }
      }
    }
    if (f_corners == 0 && f_near == 0) return;
    const Vector3d& n_m = s_.normals[0].Get(m.id, [&] { return UnitNormal(m.corners); });
    std::array<double, 3> f_off;
    for (int j = 0; j < 3; ++j) f_off[j] = n_m.dot(f.corners[j] - m.corners[0]);
    for (unsigned j_bits = f_corners; j_bits != 0; j_bits &= j_bits - 1) {
      const int j = std::countr_zero(j_bits);
      const Vector3d& p = f.corners[j];
      if (std::abs(f_off[j]) > tol || !s_.Locate(1, f.vertex(j), m.id)) {
        continue;
      }
      const Vector3d q = ClosestPointOnTriangle(p, m.corners[0], m.corners[1], m.corners[2]);
      if ((q - p).norm() <= tol) {
        Add(p, FeatureHolding(m, q, tol), {FeatureKind::kVertex, f.vertex(j)}, -n_m, -n_m);
      }
    }
    f_near &= NearEdges(f_off, tol);
    if (f_near == 0) return;
    const FaceEdges& f_edges = fixed_edges->edges;
    const FaceEdges m_edges(m.corners);
    for (unsigned i_bits = m_near; i_bits != 0; i_bits &= i_bits - 1) {
      const int i = std::countr_zero(i_bits);
      const Vector3d &p1 = m.corners[i], &q1 = m.corners[(i + 1) % 3];
      for (unsigned j_bits = f_near; j_bits != 0; j_bits &= j_bits - 1) {
        const int j = std::countr_zero(j_bits);
        if (BoxesApart(m_edges.lo[i], m_edges.hi[i], f_edges.lo[j], f_edges.hi[j], tol)) continue;
        const Vector3d &p2 = f.corners[j], &q2 = f.corners[(j + 1) % 3];
        // The lines through the edges more than 2 tolerances apart (the
        // segments are at least as far): no edge-edge contact.
        const Vector3d across = m_edges.along[i].cross(f_edges.along[j]);
        const double gap = across.dot(p2 - p1);
        if (gap * gap > 4 * tol * tol * across.squaredNorm()) continue;
        const SegmentClosest s = ClosestPointsOfSegments(p1, q1, p2, q2);
        if ((s.on_first - s.on_second).norm() > tol) continue;
        // Ends within the tolerance are vertex contacts, found above.
        if (std::min(s.s, 1 - s.s) * m_edges.along[i].norm() <= tol) continue;
        if (std::min(s.t, 1 - s.t) * f_edges.along[j].norm() <= tol) continue;
        Add((s.on_first + s.on_second) / 2, m.edge_feature(i), f.edge_feature(j),
            across.squaredNorm() > 0 ? across.normalized() : across, n_f);
      }
    }
  }

  void Finish(LocatedContacts& out) {
    // Every entry counts toward the normal, those of one feature pair too:
    // a vertex on an edge meets the faces on both sides of it (once each),
    // and keeping one of them would tilt the normal toward that face.
    Vector3d normal_sum = Vector3d::Zero();
    for (const Entry& e : points_) normal_sum += e.normal;
    // One entry per feature pair, in feature order, the first one added kept
    // (a sort by order of addition within a pair: std::stable_sort would
    // allocate a buffer).
    std::sort(points_.begin(), points_.end(), [](const Entry& x, const Entry& y) {
      return std::tie(x.features, x.order) < std::tie(y.features, y.order);
    });
    points_.erase(
        std::unique(points_.begin(), points_.end(),
                    [](const Entry& x, const Entry& y) { return x.features == y.features; }),
        points_.end());
    out.points.clear();
    std::vector<VertexId>(&vertices)[2] = s_.vertices;
    std::vector<EdgeId>(&edges)[2] = s_.edges;
    std::vector<FaceId>(&faces)[2] = s_.faces;
    auto collect = [&](int side, const Feature& feature) {
      if (feature.kind == FeatureKind::kVertex) vertices[side].push_back(feature.id);
      if (feature.kind == FeatureKind::kEdge) edges[side].push_back(feature.id);
      if (feature.kind == FeatureKind::kFace) faces[side].push_back(feature.id);
    };
    for (const Entry& e : points_) {
      out.points.push_back(ContactPointF{e.p, e.features.first, e.features.second});
      collect(0, e.features.first);
      collect(1, e.features.second);
    }
    AggregateSide(c_.moving, vertices[0], edges[0], faces[0], out.moving);
    AggregateSide(c_.fixed, vertices[1], edges[1], faces[1], out.fixed);
    // A face contact's own faces give its normal: corner and edge entries
    // of aligned faces also meet the side faces at the rim, whose normals
    // would tilt the sum.
    if (out.fixed.kind == FeatureKind::kFace) {
      normal_sum = FacesNormal(c_.fixed, Isometry3d::Identity(), out.fixed.faces);
    } else if (out.moving.kind == FeatureKind::kFace) {
      normal_sum = -FacesNormal(c_.moving, X_FM_, out.moving.faces);
    }
    out.normal_F = normal_sum.squaredNorm() > 1e-24 ? Oriented(normal_sum.normalized(), normal_sum)
                                                    : -c_.direction_F;
  }

 private:
  // `normal` turned to oppose the motion (a soup has no reliable outside),
  // unless the motion runs along the surface: then a rounding-sized tilt
  // would flip it, so the mesh's own orientation (`outward`: the fixed
  // face's normal, or the moving face's reversed) decides.
  Vector3d Oriented(Vector3d normal, const Vector3d& outward) const {
    constexpr double kAlongSurface = 1e-6;  // |cos| of the angle between normal and D
    const double along = normal.dot(c_.direction_F);
    if (std::abs(along) > kAlongSurface * normal.norm()) {
      if (along > 0) normal = -normal;
    } else if (normal.dot(outward) < 0) {
      normal = -normal;
    }
    return normal;
  }

  // Records a contact point with its normal, oriented.
  void Add(const Vector3d& p, const Feature& moving, const Feature& fixed, const Vector3d& normal,
           const Vector3d& outward) {
    points_.push_back(
        {{moving, fixed}, p, Oriented(normal, outward), static_cast<int>(points_.size())});
  }

  // The sum of the unit normals of `faces` of `object` posed at X_FO.
  static Vector3d FacesNormal(const HapticObject& object, const Isometry3d& X_FO,
                              const std::vector<FaceId>& faces) {
    Vector3d sum = Vector3d::Zero();
    for (FaceId f : faces) {
      const auto& v = object.face(f).vertices;
      sum += UnitNormal({X_FO * object.position(v[0]), X_FO * object.position(v[1]),
                         X_FO * object.position(v[2])});
    }
    return sum;
  }

  struct Entry {
    std::pair<Feature, Feature> features;
    Vector3d p;
    Vector3d normal;
    int order;  // of addition
  };

  // A corner of one side (0: moving, 1: fixed) against a face of the other.
  static uint64_t CornerKey(int side, VertexId corner, FaceId face) {
    return (uint64_t{static_cast<uint32_t>(corner)} << 32 | static_cast<uint32_t>(face)) << 1 |
           static_cast<uint64_t>(side);
  }

  // Buffers kept from one query to the next (common/core/scratch.h) so
  // that a steady stream of queries does not allocate.
  struct Storage {
    std::vector<Entry> points;
    // The first face each corner of a side (0: moving, 1: fixed) was
    // located against: most corners meet one face only. The CornerKeys of
    // the others located so far: a set emptied key by key (its clear()
    // gives a large table back), with the keys in order of insertion.
    IdMemo<FaceId> first_face[2];
    absl::flat_hash_set<uint64_t> located;
    std::vector<uint64_t> located_keys;
    std::vector<VertexId> vertices[2];
    std::vector<EdgeId> edges[2];
    std::vector<FaceId> faces[2];
    // M's vertices in F's frame, and the unit normals of the faces of
    // either side (0: moving, 1: fixed), each computed once per call.
    PlacedVertices moving_vertices;
    IdMemo<Vector3d> normals[2];
    // The edges of F's faces met so far (an index into fixed_edges), each
    // face's taken once per call: a face of F is in many pairs.
    IdMemo<int> fixed_edges_at;
    std::vector<FixedFaceEdges> fixed_edges;

    const FixedFaceEdges& FixedEdges(FaceId face, const Triangle3d& corners,
                                     const Vector3d& unit_normal) {
      return fixed_edges[fixed_edges_at.Get(face, [&] {
        fixed_edges.emplace_back(corners, unit_normal);
        return static_cast<int>(fixed_edges.size()) - 1;
      })];
    }

    // Whether `corner` of `side` is yet to be located against `face`; from
    // now on it is.
    bool Locate(int side, VertexId corner, FaceId face) {
      bool first = false;
      const FaceId first_face_located = first_face[side].Get(corner, [&] {
        first = true;
        return face;
      });
      if (first) return true;
      if (first_face_located == face) return false;
      const uint64_t key = CornerKey(side, corner, face);
      if (!located.insert(key).second) return false;
      located_keys.push_back(key);
      return true;
    }
    void Reset() {
      for (const uint64_t key : located_keys) located.erase(key);
      located_keys.clear();
      points.clear();
      fixed_edges.clear();
      for (int side = 0; side < 2; ++side) {
        vertices[side].clear();
        edges[side].clear();
        faces[side].clear();
      }
    }
  };
  static Storage& storage() { return Scratch<Storage>(); }

  // How far outside a face of M's box a corner of F may be and still be
  // within the tolerance of the face, as computed: twice the tolerance,
  // and 1e-12 of the largest coordinate either object can have here for
  // the rounding of the closest point and its distance.
  static double CornerSlack(const ContactContext& c, const Isometry3d& X_FM) {
    const auto reach = [](const AlignedBox3d& box) {
      return box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).norm();
    };
    const double largest = std::max(reach(c.fixed.bounding_box()),
                                    reach(c.moving.bounding_box()) + X_FM.translation().norm());
    return 2 * c.tolerance_m + 1e-12 * largest;
  }

  const ContactContext& c_;
  const Isometry3d X_FM_;
  const double corner_slack_;
  Storage& s_;
  std::vector<Entry>& points_;
};

}  // namespace

void LocateContacts(const ContactContext& context, const Isometry3d& X_FM,
                    std::span<const TrianglePair> pairs, LocatedContacts& out) {
  Locator locator(context, X_FM);
  for (const TrianglePair& pair : pairs) locator.AddPair(pair);
  locator.Finish(out);
}

}  // namespace hs
