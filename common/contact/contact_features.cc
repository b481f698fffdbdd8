#include "common/contact/contact_features.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <tuple>

#include "absl/container/flat_hash_set.h"

#include "common/contact/closest_points.h"
#include "common/contact/near_features_batch.h"
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
  const Triangle3d& corners;

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

// Whether boxes [lo1, hi1] and [lo2, hi2] are more than `tol` apart along
// some axis.
bool BoxesApart(const Vector3d& lo1, const Vector3d& hi1, const Vector3d& lo2, const Vector3d& hi2,
                double tol) {
  for (int d = 0; d < 3; ++d) {
    if (hi1[d] + tol < lo2[d] || hi2[d] + tol < lo1[d]) return true;
  }
  return false;
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
    s_.normals.Reset(c.moving.num_faces());
    s_.fixed_face_at.Reset(c.fixed.num_faces());
  }
  Locator(const Locator&) = delete;
  Locator& operator=(const Locator&) = delete;

  // Locates the contacts of every pair: the first tests of all of them in
  // lanes, then the exact tests of the features those leave, pair by pair
  // in order.
  void AddPairs(std::span<const TrianglePair> pairs) {
    std::vector<MovingFaceCorners>& moving = s_.moving_faces;
    std::vector<FaceRecordPair>& records = s_.record_pairs;
    moving.clear();
    records.clear();
    FaceId moving_face = -1;  // the last pair's (a run of pairs shares it)
    for (const TrianglePair& pair : pairs) {
      if (pair.a != moving_face) {
        moving.push_back({s_.moving_vertices.Face(pair.a)});
        moving_face = pair.a;
      }
      const int fixed = s_.fixed_face_at.Get(pair.b, [&] {
        s_.fixed_faces.emplace_back(c_.FixedTriangle(pair.b));
        return static_cast<int>(s_.fixed_faces.size()) - 1;
      });
      records.push_back({static_cast<int32_t>(moving.size()) - 1, fixed});
    }
    std::vector<NearFeatures>& near = s_.near;
    if (near.size() < pairs.size()) near.resize(pairs.size());
    NearFeaturesBatch(moving.data(), s_.fixed_faces.data(), records, c_.tolerance_m, corner_slack_,
                      std::span(near).first(pairs.size()));
    for (size_t k = 0; k < pairs.size(); ++k) {
      AddPair(pairs[k], moving[records[k].moving].corners, s_.fixed_faces[records[k].fixed],
              near[k]);
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
  // The exact tests of the features of pair (m, f) that the first tests
  // (`near`) leave: a corner within the tolerance of the other face's plane
  // may be within the tolerance of the face; an edge of M near F's plane
  // and an edge of F near M's, of each other. A corner meets the other face
  // alike from every face around it: each (corner, face) is located once.
  void AddPair(const TrianglePair& pair, const Triangle3d& m_corners, const FixedFaceEdges& f_face,
               NearFeatures near) {
    const PosedFace m{&c_.moving, pair.a, m_corners};
    const PosedFace f{&c_.fixed, pair.b, f_face.corners};
    const double tol = c_.tolerance_m;
    const Vector3d& n_f = f_face.unit_normal;
    for (unsigned i_bits = near.moving_corners; i_bits != 0; i_bits &= i_bits - 1) {
      const int i = std::countr_zero(i_bits);
      const Vector3d& p = m.corners[i];
      if (!s_.Locate(0, m.vertex(i), f.id)) continue;
      const Vector3d q = ClosestPointOnTriangle(p, f.corners[0], f.corners[1], f.corners[2]);
      if ((q - p).norm() <= tol) {
        Add(p, {FeatureKind::kVertex, m.vertex(i)}, FeatureHolding(f, q, tol), n_f, n_f);
      }
    }
    // F's side needs M's face's normal only for what is near M's face (a
    // face of F is mostly far larger).
    if (near.fixed_corners == 0 && near.fixed_edges == 0) return;
    const Vector3d& n_m = s_.normals.Get(m.id, [&] { return UnitNormal(m.corners); });
    std::array<double, 3> f_off;
    for (int j = 0; j < 3; ++j) f_off[j] = n_m.dot(f.corners[j] - m.corners[0]);
    for (unsigned j_bits = near.fixed_corners; j_bits != 0; j_bits &= j_bits - 1) {
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
    // An edge whose ends lie beyond the tolerance on one side of the other
    // face's plane is farther than it from every edge of that face.
    const unsigned f_near = near.fixed_edges & NearEdges(f_off, tol);
    if (f_near == 0) return;
    const FaceEdges& f_edges = f_face.edges;
    const FaceEdges m_edges(m.corners);
    for (unsigned i_bits = near.moving_edges; i_bits != 0; i_bits &= i_bits - 1) {
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
    // M's vertices in F's frame, and the unit normals of its faces, each
    // computed once per call.
    PlacedVertices moving_vertices;
    IdMemo<Vector3d> normals;
    // F's faces met so far (an index into fixed_faces), each taken once per
    // call: a face of F is in many pairs.
    IdMemo<int> fixed_face_at;
    std::vector<FixedFaceEdges> fixed_faces;
    // The pairs' faces of M (one per run of pairs that shares it), each
    // pair's faces and what the first tests tell of it.
    std::vector<MovingFaceCorners> moving_faces;
    std::vector<FaceRecordPair> record_pairs;
    std::vector<NearFeatures> near;

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
      fixed_faces.clear();
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
  locator.AddPairs(pairs);
  locator.Finish(out);
}

}  // namespace hs
