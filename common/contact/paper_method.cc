#include "common/contact/paper_method.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "common/contact/projection_options.h"
#include "common/contact/side_contact.h"

// The paper's method (s.4, fig. 5 and 6, appendix), as docs/algorithm.md
// reads it, with one reading changed (see PenetrationTest in
// projection_options.h): for each plane xy, yz, xz of F's frame, project the
// candidate features, back every penetrating vertex of M along the projected
// direction past every candidate edge of F behind it (d_maxm), do the same
// with F's vertices against M's edges (the singular case, d_maxf), and turn
// the larger into a 3D distance along D. The smallest over the planes is the
// depth: separating the projections in one plane separates the objects.
//
// How the tolerance tau = context.tolerance_m (metres) is used. Projection
// drops one coordinate, so it moves no point by more than it moves in 3D:
// in-plane lengths are metres and a 3D tolerance of tau is a 2D tolerance of
// tau. Every in-plane comparison therefore uses tau itself:
//  - a candidate edge meets the line through a vertex when an endpoint is
//    within tau of the line or the endpoints are on opposite sides of it
//    ("P on the segment, within the tolerance");
//  - a crossing is behind the vertex when d >= -tau (touching counts, and
//    its depth is clamped to 0);
//  - a vertex is a contact vertex when its d_i is within tau of the plane's
//    d_plane.
// Only the choice between planes compares 3D distances t = d / |D_p|, with
// tau again (ties between planes are within tau of each other).

namespace hs {
namespace {

using Vector2d = Eigen::Vector2d;

constexpr double kInf = std::numeric_limits<double>::infinity();

// D is unit, so |D_p| is the sine of the angle between D and the plane's
// normal. Below this the plane is skipped (depth +inf): t = d / |D_p| blows up
// as D turns perpendicular to the plane, multiplying the in-plane rounding
// (~1e-16 x size) by 1 / |D_p|; at 1e-6 that is still ~1e-10 x size, well
// under the default tolerance of 1e-9 x size. Closer to perpendicular the
// plane cannot separate anything along D anyway: the projections barely move.
constexpr double kMinProjectedDirection = 1e-6;

// The two coordinates each plane keeps, in ContactSetF::plane_depths_m order:
// xy drops z, yz drops x, xz drops y.
constexpr int kPlaneAxes[3][2] = {{0, 1}, {1, 2}, {0, 2}};

Vector2d Project(const Vector3d& p, int plane) {
  return {p[kPlaneAxes[plane][0]], p[kPlaneAxes[plane][1]]};
}

double Cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A candidate vertex or edge. Positions are in F's frame relative to an
// anchor point near the contact, so that objects far from F's origin do not
// lose the contact's digits to cancellation in the 2D cross products.
struct CandidateVertex {
  VertexId id;
  Vector3d p;
};
struct CandidateEdge {
  EdgeId id;
  VertexId va, vb;
  Vector3d a, b;
};

// One side's candidates: the vertices, edges and triangles of its faces that
// appear in the intersecting pairs, each once, in id order.
struct Candidates {
  std::vector<CandidateVertex> vertices;
  std::vector<CandidateEdge> edges;
  std::vector<Triangle3d> triangles;
};

// A set of ids below a count, as one bit each: marking is a store, and the
// ids come out in increasing order by a scan of the words, with no sort.
class IdMarks {
 public:
  explicit IdMarks(int count) : words_((count + 63) / 64, 0) {}

  void Mark(int id) { words_[id >> 6] |= uint64_t{1} << (id & 63); }

  template <typename Id>
  std::vector<Id> Sorted() const {
    std::vector<Id> ids;
    for (size_t w = 0; w < words_.size(); ++w) {
      for (uint64_t bits = words_[w]; bits != 0; bits &= bits - 1) {
        ids.push_back(static_cast<Id>(64 * w + std::countr_zero(bits)));
      }
    }
    return ids;
  }

 private:
  std::vector<uint64_t> words_;
};

template <typename PositionOf>
Candidates Gather(const HapticObject& object, std::span<const FaceId> paired_faces,
                  PositionOf position_of) {
  IdMarks face_marks(object.num_faces());
  for (FaceId f : paired_faces) face_marks.Mark(f);
  const std::vector<FaceId> faces = face_marks.Sorted<FaceId>();
  IdMarks corner_marks(object.num_vertices()), side_marks(object.num_edges());
  for (FaceId f : faces) {
    const Face& face = object.face(f);
    for (VertexId v : face.vertices) corner_marks.Mark(v);
    for (EdgeId e : face.edges) side_marks.Mark(e);
  }
  Candidates c;
  // Each vertex placed once; the edges and triangles look their ends up.
  std::vector<Vector3d> placed(object.num_vertices());
  for (VertexId v : corner_marks.Sorted<VertexId>()) {
    placed[v] = position_of(v);
    c.vertices.push_back({v, placed[v]});
  }
  for (EdgeId e : side_marks.Sorted<EdgeId>()) {
    const Edge& edge = object.edge(e);
    c.edges.push_back({e, edge.vertices[0], edge.vertices[1], placed[edge.vertices[0]],
                       placed[edge.vertices[1]]});
  }
  c.triangles.reserve(faces.size());
  for (FaceId f : faces) {
    const auto& v = object.face(f).vertices;
    c.triangles.push_back(Triangle3d{placed[v[0]], placed[v[1]], placed[v[2]]});
  }
  return c;
}

// Where the line through a vertex meets a segment: d_ij, and whether that
// point P is within the tolerance of the segment's ends.
struct Crossing {
  double d;
  bool at_a;
  bool at_b;
};

// The paper's d_ij for vertex v and segment [a, b] in one plane: the largest
// (v - P).u over the points P of the segment on the line through v along u
// (u unit). Points within `tol` of the line count, so an endpoint grazed
// within the tolerance is a crossing, and an edge running along the line
// (parallel, or projected to a point) contributes its endpoints: the limit
// of the crossing as the edge turns parallel, which also keeps the answer
// when the neighbouring edges that would cover those endpoints are not
// candidates. Nothing when the line misses the segment.
std::optional<Crossing> CrossingDepth(const Vector2d& v, const Vector2d& u, const Vector2d& a,
                                      const Vector2d& b, double length, double tol) {
  const Vector2d va = a - v, vb = b - v;
  // Signed distances of the endpoints from the line, and their positions
  // behind v along it; no division, so no blow-up near parallel.
  const double ha = Cross(u, va), hb = Cross(u, vb);
  const double ga = -u.dot(va), gb = -u.dot(vb);
  double best = -kInf;
  double r_best = 0;  // where along [a, b] the best point lies
  if (std::abs(ha) <= tol && ga > best) best = ga, r_best = 0;
  if (std::abs(hb) <= tol && gb > best) best = gb, r_best = 1;
  if ((ha < 0 && hb > 0) || (ha > 0 && hb < 0)) {
    const double r = ha / (ha - hb);  // in [0, 1]: the endpoints straddle the line
    const double g = ga + r * (gb - ga);
    if (g > best) best = g, r_best = r;
  }
  if (best == -kInf) return std::nullopt;
  return Crossing{best, r_best * length <= tol, (1 - r_best) * length <= tol};
}

double SegmentDistance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double r = len_sq > 0 ? std::clamp((p - a).dot(ab) / len_sq, 0.0, 1.0) : 0.0;
  return (a + r * ab - p).norm();
}

// Whether p lies in the closed triangle t, or within `tol` of it. A
// triangle seen edge-on (zero projected area) is a segment: only the
// distance test can hold.
bool InsideTriangle(const Vector2d& p, const std::array<Vector2d, 3>& t, double tol) {
  const double area2 = Cross(t[1] - t[0], t[2] - t[0]);
  if (area2 != 0) {
    const double s0 = Cross(t[1] - t[0], p - t[0]);
    const double s1 = Cross(t[2] - t[1], p - t[1]);
    const double s2 = Cross(t[0] - t[2], p - t[2]);
    if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return true;
  }
  for (int k = 0; k < 3; ++k) {
    if (SegmentDistance(p, t[k], t[(k + 1) % 3]) <= tol) return true;
  }
  return false;
}

// A crossing kept by a pass: vertex and edge are indices into the pass's
// candidate arrays; d in plane metres, >= -tol.
struct Hit {
  int vertex;
  int edge;
  double d;
  bool at_a, at_b;  // the crossing is at (within tol of) the edge's ends
};

// One pass of one plane: the paper's loop of vertices of one object against
// the edges of the other.
struct PassResult {
  /// Every crossing with d >= max(-tol, d_max - tol), and some below it:
  /// only those can reach d_plane - tol, as d_plane >= d_max.
  std::vector<Hit> hits;
  /// Largest d over the crossings with d >= -tol, clamped to >= 0
  /// (touching is depth 0); -inf when no vertex penetrates.
  double d_max = -kInf;
  /// The pass stopped once its depth reached `stop_t` less the tolerance:
  /// d_max is then only a lower bound of the pass's largest d.
  bool cut_short = false;
};

// Vertices of one side against edges of the other, the line through each
// vertex along `u`: d_ij = (V - P_ij).u, kept when >= -tol and within tol
// of the deepest so far. Stops once d_max / `norm` (|D_p|: the depth along
// D) + tol >= `stop_t`, the very expression the choice between planes
// compares, so that a plane stopped is one that choice would pass over.
//
// In steps: project the edge side's segments, place the vertices and the
// segments across and along the line, then scan, each vertex against every
// band when the vertices are few, else against the buckets its line falls
// in.
class Pass {
 public:
  Pass(const Candidates& vertex_side, const Candidates& edge_side, int plane, const Vector2d& u,
       double tol, const ProjectionOptions& options, double norm, double stop_t)
      : plane_(plane),
        u_(u),
        w_(-u.y(), u.x()),
        tol_(tol),
        options_(options),
        norm_(norm),
        stop_t_(stop_t) {
    ProjectEdgeSide(edge_side);
    PlaceVertices(vertex_side);
    PlaceSegments();
  }

  PassResult Run() {
    constexpr int kFewVertices = 16;
    if (num_vertices_ <= kFewVertices) {
      ScanEveryBand();
    } else {
      BuildBuckets();
      ScanBuckets();
    }
    return std::move(result_);
  }

 private:
  // Each segment's ends across the line (key, along w) and along it (back,
  // along u), and the slack of its band for the tolerance and rounding.
  struct Ends {
    double key_a, key_b, back_a, back_b, slack;
  };
  // A segment listed in a bucket, with the least u over its part that the
  // lines through the bucket's vertices can meet.
  struct Entry {
    double behind;
    int segment;
  };

  void ProjectEdgeSide(const Candidates& edge_side) {
    segments_.reserve(edge_side.edges.size());
    for (const CandidateEdge& e : edge_side.edges) {
      segments_.push_back({Project(e.a, plane_), Project(e.b, plane_)});
    }
    if (options_.penetration == PenetrationTest::kInsideTriangle) {
      triangles_.reserve(edge_side.triangles.size());
      for (const Triangle3d& t : edge_side.triangles) {
        triangles_.push_back({Project(t[0], plane_), Project(t[1], plane_), Project(t[2], plane_)});
      }
    }
    num_segments_ = static_cast<int>(segments_.size());
  }

  // A segment can meet the line through v along u only if its band, its
  // extent across the line along w = u turned by 90 degrees, holds v.w
  // within the tolerance (CrossingDepth's rule; the band is widened for
  // rounding). Buckets over v.w list the segments whose band meets them,
  // so each vertex tests only the segments near its line instead of all;
  // a handful of vertices check every band instead.
  void PlaceVertices(const Candidates& vertex_side) {
    num_vertices_ = static_cast<int>(vertex_side.vertices.size());
    points_.resize(num_vertices_);
    keys_.resize(num_vertices_);
    backs_.resize(num_vertices_);
    sizes_.resize(num_vertices_);
    for (int i = 0; i < num_vertices_; ++i) {
      points_[i] = Project(vertex_side.vertices[i].p, plane_);
      keys_[i] = points_[i].dot(w_);
      backs_[i] = points_[i].dot(u_);
      sizes_[i] = points_[i].cwiseAbs().sum();
      key_lo_ = std::min(key_lo_, keys_[i]);
      key_hi_ = std::max(key_hi_, keys_[i]);
    }
    // The deepest vertex first: what can still matter rises at once.
    deepest_first_.resize(num_vertices_);
    for (int i = 0; i < num_vertices_; ++i) deepest_first_[i] = i;
    if (num_vertices_ > 0) {
      std::swap(deepest_first_[0],
                deepest_first_[std::max_element(backs_.begin(), backs_.end()) - backs_.begin()]);
    }
  }

  // No point of segment j lies further back along u than its end `ahead[j]`
  // = min(a.u, b.u), so v's d_j is at most v.u - ahead[j] (plus rounding).
  void PlaceSegments() {
    ends_.resize(num_segments_);
    bands_.resize(num_segments_);
    ahead_.resize(num_segments_);
    lengths_.resize(num_segments_);
    for (int j = 0; j < num_segments_; ++j) {
      largest_segment_ = std::max(
          largest_segment_, segments_[j][0].cwiseAbs().sum() + segments_[j][1].cwiseAbs().sum());
      lengths_[j] = (segments_[j][1] - segments_[j][0]).norm();
      Ends& e = ends_[j];
      e.key_a = segments_[j][0].dot(w_), e.key_b = segments_[j][1].dot(w_);
      e.back_a = segments_[j][0].dot(u_), e.back_b = segments_[j][1].dot(u_);
      e.slack = 2 * tol_ + 1e-12 * (std::abs(e.key_a) + std::abs(e.key_b));
      bands_[j] = {std::min(e.key_a, e.key_b) - e.slack, std::max(e.key_a, e.key_b) + e.slack};
      ahead_[j] = std::min(e.back_a, e.back_b);
    }
  }

  // The least d that still matters: -tol, or tol under the deepest d so far
  // (without skip_shallow_crossings, -tol: every crossing is computed).
  double Matters() const {
    return options_.skip_shallow_crossings ? std::max(-tol_, result_.d_max - tol_) : -tol_;
  }

  // Whether segment j, with no point a line through vertex i meets further
  // back along u than `behind`, cannot give a d that matters; rounding,
  // relative to the coordinates, may lift d a hair over its bound.
  bool OutOfReach(int i, double behind) const {
    return options_.skip_shallow_crossings &&
           backs_[i] - behind + 1e-12 * (sizes_[i] + largest_segment_) < Matters();
  }

  // Vertex i against segment j: keeps the crossing if it matters.
  void Cross(int i, int j) {
    const std::optional<Crossing> c =
        CrossingDepth(points_[i], u_, segments_[j][0], segments_[j][1], lengths_[j], tol_);
    if (c && c->d >= Matters()) {
      result_.hits.push_back({i, j, c->d, c->at_a, c->at_b});
      result_.d_max = std::max(result_.d_max, std::max(c->d, 0.0));
      result_.cut_short = result_.d_max / norm_ + tol_ >= stop_t_;
    }
  }

  bool PenetrationTestPasses(int i) const {
    return options_.penetration != PenetrationTest::kInsideTriangle ||
           std::any_of(triangles_.begin(), triangles_.end(),
                       [&](const auto& t) { return InsideTriangle(points_[i], t, tol_); });
  }

  void ScanEveryBand() {
    for (int i : deepest_first_) {
      if (!PenetrationTestPasses(i)) continue;
      for (int j = 0; j < num_segments_; ++j) {
        if (bands_[j][0] <= keys_[i] && keys_[i] <= bands_[j][1] && !OutOfReach(i, ahead_[j])) {
          Cross(i, j);
          if (result_.cut_short) return;
        }
      }
    }
  }

  // Clamped before the cast, which then floors (the value is >= 0).
  int BucketOf(double key) const {
    return static_cast<int>(
        std::clamp((key - key_lo_) / bucket_width_, 0.0, static_cast<double>(num_buckets_ - 1)));
  }

  // Buckets about as wide as a band: narrower ones list each segment many
  // times over (the listing then costs more than the tests it saves),
  // wider ones hold more segments that miss the line. Bucket b lists
  // entries_[bucket_start_[b] .. bucket_start_[b + 1]) (a counting sort):
  // the segments whose band meets it, each with a bound on their d tighter
  // than `ahead`.
  void BuildBuckets() {
    double band_sum = 0;
    for (const auto& band : bands_) band_sum += band[1] - band[0];
    bucket_width_ = std::max({(key_hi_ - key_lo_) / std::max(1, num_segments_),
                              band_sum / std::max(1, num_segments_), 1e-300});
    num_buckets_ = std::clamp(static_cast<int>((key_hi_ - key_lo_) / bucket_width_) + 1, 1,
                              std::max(1, num_segments_));
    std::vector<std::array<int, 2>> segment_buckets(num_segments_, {0, -1});
    bucket_start_.assign(num_buckets_ + 1, 0);
    for (int j = 0; j < num_segments_; ++j) {
      if (bands_[j][1] < key_lo_ || bands_[j][0] > key_hi_) continue;
      segment_buckets[j] = {BucketOf(bands_[j][0]), BucketOf(bands_[j][1])};
      for (int b = segment_buckets[j][0]; b <= segment_buckets[j][1]; ++b) ++bucket_start_[b + 1];
    }
    for (int b = 0; b < num_buckets_; ++b) bucket_start_[b + 1] += bucket_start_[b];
    entries_.resize(bucket_start_[num_buckets_]);
    std::vector<int> cursor(bucket_start_.begin(), bucket_start_.end() - 1);
    for (int j = 0; j < num_segments_; ++j) {
      for (int b = segment_buckets[j][0]; b <= segment_buckets[j][1]; ++b) {
        entries_[cursor[b]++] = {Behind(j, b), j};
      }
    }
    // Each bucket by `behind`: a vertex stops at the first segment whose
    // bound cannot matter, and most vertices of a deep contact stop early.
    if (options_.skip_shallow_crossings) {
      for (int b = 0; b < num_buckets_; ++b) {
        std::sort(entries_.begin() + bucket_start_[b], entries_.begin() + bucket_start_[b + 1],
                  [](const Entry& x, const Entry& y) { return x.behind < y.behind; });
      }
    }
  }

  // The least u over the part of segment j that the lines through bucket
  // b's vertices can meet (with the band's slack).
  double Behind(int j, int b) const {
    const double ka = ends_[j].key_a, kb = ends_[j].key_b;
    const double ua = ends_[j].back_a, ub = ends_[j].back_b;
    // The band's slack, and the rounding of the bucket's edges.
    const double slack = ends_[j].slack + 1e-12 * (std::abs(key_lo_) + std::abs(key_hi_));
    // The bucket's keys, the lowest and highest buckets open-ended.
    const double k0 = b == 0 ? -kInf : key_lo_ + b * bucket_width_ - slack;
    const double k1 = b == num_buckets_ - 1 ? kInf : key_lo_ + (b + 1) * bucket_width_ + slack;
    double behind = std::min(ua, ub);
    if (kb != ka) {  // u is linear along the segment: least at an end of its part
      const double t0 = std::clamp((k0 - ka) / (kb - ka), 0.0, 1.0);
      const double t1 = std::clamp((k1 - ka) / (kb - ka), 0.0, 1.0);
      behind = std::max(behind, std::min(ua + t0 * (ub - ua), ua + t1 * (ub - ua)));
    }
    return behind;
  }

  void ScanBuckets() {
    for (int i : deepest_first_) {
      if (!PenetrationTestPasses(i)) continue;
      const int b = BucketOf(keys_[i]);
      for (int k = bucket_start_[b]; k < bucket_start_[b + 1]; ++k) {
        const Entry& e = entries_[k];
        if (OutOfReach(i, e.behind)) break;  // and so is the rest of the bucket
        const std::array<double, 2>& band = bands_[e.segment];
        if (keys_[i] < band[0] || band[1] < keys_[i]) continue;  // misses the line
        Cross(i, e.segment);
        if (result_.cut_short) return;
      }
    }
  }

  const int plane_;
  const Vector2d u_, w_;
  const double tol_;
  const ProjectionOptions& options_;
  const double norm_, stop_t_;

  // The edge side's segments (and triangles, for kInsideTriangle), projected.
  std::vector<std::array<Vector2d, 2>> segments_;
  std::vector<std::array<Vector2d, 3>> triangles_;
  int num_segments_ = 0;
  // The vertices: projected, v.w, v.u, |v| (L1), and the scan's order.
  int num_vertices_ = 0;
  std::vector<Vector2d> points_;
  std::vector<double> keys_, backs_, sizes_;
  std::vector<int> deepest_first_;
  double key_lo_ = kInf, key_hi_ = -kInf;
  // The segments, placed.
  std::vector<Ends> ends_;
  std::vector<std::array<double, 2>> bands_;
  std::vector<double> ahead_, lengths_;
  double largest_segment_ = 0;  // |a| + |b|, L1
  // The buckets, when the vertices are many.
  double bucket_width_ = 0;
  int num_buckets_ = 0;
  std::vector<int> bucket_start_;
  std::vector<Entry> entries_;

  PassResult result_;
};

struct PlaneResult {
  bool found = false;
  /// d_plane = max(d_maxm, d_maxf), plane metres.
  double d_plane = 0;
  /// t_plane = d_plane / |D_p|, metres along D.
  double t = kInf;
  PassResult moving;  // M's vertices against F's edges, along u_p
  PassResult fixed;   // F's vertices against M's edges, along -u_p (fig. 6)
  /// A pass stopped early: t is only a lower bound of the plane's depth.
  bool cut_short = false;
};

// The contact vertices of one pass: those whose d_i reaches d_plane within
// tol, in id order, each with the candidate index of its deepest edge
// (lowest id on ties) for its contact point.
struct PassContacts {
  std::vector<VertexId> vertices;
  std::vector<std::pair<int, int>> vertex_edge;  // candidate indices
};

PassContacts Contacts(const PassResult& pass, const Candidates& vertex_side, double d_plane,
                      double tol) {
  std::vector<int> best(vertex_side.vertices.size(), -1);
  for (int h = 0; h < static_cast<int>(pass.hits.size()); ++h) {
    const Hit& hit = pass.hits[h];
    if (hit.d < d_plane - tol) continue;
    // The lowest edge (candidates are in id order) on ties.
    const int b = best[hit.vertex];
    if (b < 0 || hit.d > pass.hits[b].d ||
        (hit.d == pass.hits[b].d && hit.edge < pass.hits[b].edge)) {
      best[hit.vertex] = h;
    }
  }
  PassContacts c;
  for (int i = 0; i < static_cast<int>(best.size()); ++i) {
    if (best[i] < 0) continue;
    c.vertices.push_back(vertex_side.vertices[i].id);
    c.vertex_edge.emplace_back(i, pass.hits[best[i]].edge);
  }
  return c;
}

// The edges of `edge_side` that produced the pass's maxima: the paper's
// contact line segments. An edge met only at an end that is itself a
// contact vertex of its side is left out: that contact is vertex to vertex
// (or the edge lies along the line), the vertex already reports it, and
// AggregateSide adds the edge back when both its ends are contacts. Without
// this, a tie between the two passes would list every edge around a contact
// vertex, as they all project through the same point.
std::vector<EdgeId> TouchedEdges(const PassResult& pass, const Candidates& edge_side,
                                 std::span<const VertexId> edge_side_contacts, double d_plane,
                                 double tol) {
  auto is_contact = [&](VertexId v) {
    return std::binary_search(edge_side_contacts.begin(), edge_side_contacts.end(), v);
  };
  std::vector<EdgeId> edges;
  for (const Hit& hit : pass.hits) {
    if (hit.d < d_plane - tol) continue;
    const CandidateEdge& e = edge_side.edges[hit.edge];
    if ((hit.at_a && is_contact(e.va)) || (hit.at_b && is_contact(e.vb))) continue;
    edges.push_back(e.id);
  }
  return edges;
}

}  // namespace

ContactSetF ReconstructByProjection(const ContactContext& context,
                                    const ProjectionOptions& options) {
  const double tol = context.tolerance_m;
  const Vector3d& D = context.direction_F;

  std::vector<FaceId> moving_faces, fixed_faces;
  moving_faces.reserve(context.pairs.size());
  fixed_faces.reserve(context.pairs.size());
  for (const TrianglePair& pair : context.pairs) {
    moving_faces.push_back(pair.a);
    fixed_faces.push_back(pair.b);
  }
  const Vector3d anchor =
      fixed_faces.empty() ? Vector3d::Zero()
                          : context.fixed.position(context.fixed.face(fixed_faces[0]).vertices[0]);
  const Candidates moving = Gather(context.moving, moving_faces, [&](VertexId v) {
    return Vector3d(context.X_FM * context.moving.position(v) - anchor);
  });
  const Candidates fixed = Gather(context.fixed, fixed_faces, [&](VertexId v) {
    return Vector3d(context.fixed.position(v) - anchor);
  });

  ContactSetF set;
  // The caller only reconstructs pairs that intersect or touch.
  set.colliding = true;
  set.direction_F = D;
  // The paper defines no contact normal; the reversing direction -D is the
  // direction it pushes M out of F, so it stands in for one.
  set.normal_F = -D;

  // The planes in order of preference: where D projects longest first (its
  // t divides by the largest |D_p|, so it is the best conditioned), then
  // the lowest index.
  std::array<double, 3> norms;
  for (int plane = 0; plane < 3; ++plane) norms[plane] = Project(D, plane).norm();
  std::array<int, 3> order = {0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return norms[x] > norms[y]; });
  std::array<PlaneResult, 3> planes;
  // Both passes of a plane, stopping once its depth plus tol reaches `stop_t`.
  auto run = [&](int plane, double stop_t) {
    PlaneResult& r = planes[plane];
    const double norm = norms[plane];
    const Vector2d u = Project(D, plane) / norm;
    r = PlaneResult{};
    r.moving = Pass(moving, fixed, plane, u, tol, options, norm, stop_t).Run();
    if (!r.moving.cut_short)
      r.fixed = Pass(fixed, moving, plane, -u, tol, options, norm, stop_t).Run();
    r.cut_short = r.moving.cut_short || r.fixed.cut_short;
    r.found = !(r.moving.hits.empty() && r.fixed.hits.empty());
    r.d_plane = std::max(r.moving.d_max, r.fixed.d_max);
    r.t = r.found ? r.d_plane / norm : kInf;
  };
  // The first plane in that order to find anything, the reference, is run
  // in full. Each later one stops once its depth t satisfies t_ref <= t +
  // tol (rounded as the choice below rounds it; its depth only grows from
  // there): then it neither undercuts the reference by more than the
  // tolerance nor is preferred to it, and the choice is the reference
  // whatever the rest of that plane. A later plane that ends without
  // satisfying it undercuts the reference, and then every plane runs in
  // full.
  int reference = -1;
  bool undercut = false;
  for (int plane : order) {
    if (!(norms[plane] >= kMinProjectedDirection)) continue;
    const bool full = reference < 0 || options.exact_plane_depths;
    run(plane, full ? kInf : planes[reference].t);
    const PlaneResult& r = planes[plane];
    if (reference < 0) {
      if (r.found) reference = plane;
    } else if (r.found && !r.cut_short && !(planes[reference].t <= r.t + tol)) {
      undercut = true;
    }
  }
  for (int plane = 0; plane < 3; ++plane) {
    if (undercut && planes[plane].cut_short) run(plane, kInf);
    if (planes[plane].found) set.plane_depths_m[plane] = planes[plane].t;
  }

  // t_paper = min over the planes that found something; among planes within
  // tol of it, the first in the order of preference wins. Without an
  // undercut that is the reference: t_ref <= t + tol held for every plane,
  // so for the least t too.
  int chosen = reference;
  if (undercut) {
    double t_min = kInf;
    for (const PlaneResult& r : planes) {
      if (r.found) t_min = std::min(t_min, r.t);
    }
    for (int plane : order) {
      if (planes[plane].found && planes[plane].t <= t_min + tol) {
        chosen = plane;
        break;
      }
    }
  }
  if (chosen < 0) {
    // No plane saw a crossing: the pairs only graze each other.
    set.depth_m = 0;
    return set;
  }

  const PlaneResult& r = planes[chosen];
  set.depth_m = r.t;
  set.penetrating = set.depth_m > tol;
  set.reversing_vector_F = -set.depth_m * D;
  // Within tol, both passes reach d_plane and both report their vertices;
  // the singular case is when only F's vertices decide the depth.
  set.singular_case = r.fixed.d_max > r.moving.d_max + tol;

  const PassContacts m = Contacts(r.moving, moving, r.d_plane, tol);
  const PassContacts f = Contacts(r.fixed, fixed, r.d_plane, tol);
  AggregateSide(context.moving, m.vertices,
                TouchedEdges(r.fixed, moving, m.vertices, r.d_plane, tol), {}, set.moving);
  AggregateSide(context.fixed, f.vertices,
                TouchedEdges(r.moving, fixed, f.vertices, r.d_plane, tol), {}, set.fixed);

  set.points.reserve(m.vertex_edge.size() + f.vertex_edge.size());
  for (const auto& [i, j] : m.vertex_edge) {
    // M's vertex where it ends up once moved by the reversing vector.
    set.points.push_back({anchor + moving.vertices[i].p - set.depth_m * D,
                          {FeatureKind::kVertex, moving.vertices[i].id},
                          {FeatureKind::kEdge, fixed.edges[j].id}});
  }
  for (const auto& [i, j] : f.vertex_edge) {
    set.points.push_back({anchor + fixed.vertices[i].p,
                          {FeatureKind::kEdge, moving.edges[j].id},
                          {FeatureKind::kVertex, fixed.vertices[i].id}});
  }
  return set;
}

ContactSetF ReconstructByProjection(const ContactContext& context) {
  return ReconstructByProjection(context, ProjectionOptions{});
}

}  // namespace hs
