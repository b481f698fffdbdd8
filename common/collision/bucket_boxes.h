#pragma once
// The axis-aligned boxes of a leaf bucket's faces (at most 32), coordinate
// by coordinate, and which of them meet a box within a margin: a bit mask
// computed several boxes at a time in the lanes of the machine's widest
// vectors (Google Highway, the target chosen when the program runs). The
// pair traversal's box tests between two buckets (triangle_pairs.cc).

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <span>

namespace hs {

/// A box: lo[d] <= x[d] <= hi[d] in each coordinate d.
struct AxisBox {
  double lo[3], hi[3];

  /// The box that holds nothing: Include grows it to exactly the box of
  /// the boxes it is given.
  static AxisBox Empty() {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    return {{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  }
  /// Grows to hold the box of corners box_lo[0, 3) and box_hi[0, 3)
  /// (std::min and std::max: exact).
  void Include(const double* box_lo, const double* box_hi) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], box_lo[d]);
      hi[d] = std::max(hi[d], box_hi[d]);
    }
  }
};

/// Boxes kept coordinate by coordinate (a model's faces in leaf order):
/// box k is lo[d][k] <= x[d] <= hi[d][k]. Each array can be read
/// kReadPast entries past the last box a query names, so that whole
/// vectors are read.
struct BoxColumns {
  static constexpr int kReadPast = 8;  // the most lanes read at once
  const double* lo[3];
  const double* hi[3];
};

/// Bit k: whether box k of the first `count` (at most 32) of `boxes`, grown
/// by grow_lo below and grow_hi above, meets `box` within `margin`,
/// compared exactly as
///   lo[d][k] + grow_lo[d] <= box.hi[d] + margin and
///   box.lo[d] <= (hi[d][k] + grow_hi[d]) + margin
/// for every d (false where any of them is NaN).
uint32_t GrownBoxesMeeting(const BoxColumns& boxes, int count, const double (&grow_lo)[3],
                           const double (&grow_hi)[3], const AxisBox& box, double margin);

/// Boxes to meet within a margin, each kept as its low corner and its high
/// corner plus the margin.
struct BucketBoxes {
  static constexpr int kCapacity = 32;  // one bit each

  /// Empties the set, for boxes to meet within `margin`.
  void Start(double margin) {
    margin_ = margin;
    size_ = 0;
  }
  /// Appends the box of corners lo[0, 3) and hi[0, 3); at most kCapacity.
  void Add(const double* lo, const double* hi) {
    for (int d = 0; d < 3; ++d) {
      lo_[d][size_] = lo[d];
      hi_plus_margin_[d][size_] = hi[d] + margin_;
    }
    ++size_;
  }
  int size() const { return size_; }
  /// Becomes the boxes of `from` (this set itself, or another) whose bits
  /// `kept` has, in their order, with its margin.
  void Keep(const BucketBoxes& from, uint32_t kept) {
    int n = 0;
    for (; kept != 0; kept &= kept - 1, ++n) {
      const int k = std::countr_zero(kept);
      for (int d = 0; d < 3; ++d) {
        lo_[d][n] = from.lo_[d][k];
        hi_plus_margin_[d][n] = from.hi_plus_margin_[d][k];
      }
    }
    size_ = n;
    margin_ = from.margin_;
  }

  /// For each i, bit k of out[i]: whether box k meets queries[i] within
  /// the margin, compared exactly as
  ///   q.lo[d] <= (hi[d][k] + margin) and lo[d][k] <= (q.hi[d] + margin)
  /// for every d (false where any of them is NaN). `out` holds
  /// queries.size() entries.
  void Meeting(std::span<const AxisBox> queries, std::span<uint32_t> out) const;

 private:
  // Whole vectors are read past size_: what is there is never used.
  alignas(64) std::array<double, kCapacity> lo_[3] = {};
  alignas(64) std::array<double, kCapacity> hi_plus_margin_[3] = {};
  int size_ = 0;
  double margin_ = 0;
};

}  // namespace hs
