// BucketBoxes::Meeting (bucket_boxes.h) with Google Highway: written by
// hand because no library tests a box against a few dozen boxes into a bit
// mask. Each comparison is the scalar one on the same sums (one addition
// each, rounded alike in lanes), so the masks are the scalar code's.

#include "common/collision/bucket_boxes.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "common/collision/bucket_boxes.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// BucketBoxes::Meeting of `size` boxes, coordinate d's low corners at
// lo[d] and high corners plus the margin at hi_plus[d].
void MeetingLanes(const double* const* lo, const double* const* hi_plus, size_t size, double margin,
                  const AxisBox* queries, size_t n, uint32_t* out) {
  const hn::ScalableTag<double> d;
  const size_t lanes = hn::Lanes(d);
  const uint32_t valid = size == 32 ? ~uint32_t{0} : (uint32_t{1} << size) - 1;
  for (size_t i = 0; i < n; ++i) {
    const AxisBox& q = queries[i];
    hn::Vec<decltype(d)> q_lo[3], q_hi_plus[3];
    for (int c = 0; c < 3; ++c) {
      q_lo[c] = hn::Set(d, q.lo[c]);
      q_hi_plus[c] = hn::Set(d, q.hi[c] + margin);
    }
    uint32_t meets = 0;
    for (size_t k = 0; k < size; k += lanes) {
      auto meet = hn::And(hn::Le(q_lo[0], hn::Load(d, hi_plus[0] + k)),
                          hn::Le(hn::Load(d, lo[0] + k), q_hi_plus[0]));
      for (int c = 1; c < 3; ++c) {
        meet = hn::And(meet, hn::And(hn::Le(q_lo[c], hn::Load(d, hi_plus[c] + k)),
                                     hn::Le(hn::Load(d, lo[c] + k), q_hi_plus[c])));
      }
      uint8_t bits[8] = {};
      hn::StoreMaskBits(d, meet, bits);
      meets |= uint32_t{bits[0]} << k;
    }
    out[i] = meets & valid;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

HWY_EXPORT(MeetingLanes);

void BucketBoxes::Meeting(std::span<const AxisBox> queries, std::span<uint32_t> out) const {
  const double* lo[3] = {lo_[0].data(), lo_[1].data(), lo_[2].data()};
  const double* hi_plus[3] = {hi_plus_margin_[0].data(), hi_plus_margin_[1].data(),
                              hi_plus_margin_[2].data()};
  HWY_DYNAMIC_DISPATCH(MeetingLanes)
  (lo, hi_plus, static_cast<size_t>(size_), margin_, queries.data(), queries.size(), out.data());
}

}  // namespace hs
#endif
