// BucketBoxes::Meeting and GrownBoxesMeeting (bucket_boxes.h) with Google
// Highway: written by hand because no library tests a box against a few
// dozen boxes into a bit mask. Each comparison is the scalar one on the
// same sums (each addition rounded alike in lanes), so the masks are the
// scalar code's.

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

// GrownBoxesMeeting.
uint32_t GrownMeetingLanes(const BoxColumns& boxes, size_t count, const double* grow_lo,
                           const double* grow_hi, const AxisBox& box, double margin) {
  const hn::CappedTag<double, BoxColumns::kReadPast> d;
  const size_t lanes = hn::Lanes(d);
  const auto margin_v = hn::Set(d, margin);
  hn::Vec<decltype(d)> box_lo[3], box_hi_plus[3], g_lo[3], g_hi[3];
  for (int c = 0; c < 3; ++c) {
    box_lo[c] = hn::Set(d, box.lo[c]);
    box_hi_plus[c] = hn::Set(d, box.hi[c] + margin);
    g_lo[c] = hn::Set(d, grow_lo[c]);
    g_hi[c] = hn::Set(d, grow_hi[c]);
  }
  uint32_t meets = 0;
  for (size_t k = 0; k < count; k += lanes) {
    auto meet = hn::FirstN(d, count - k);
    for (int c = 0; c < 3; ++c) {
      const auto lo = hn::Add(hn::LoadU(d, boxes.lo[c] + k), g_lo[c]);
      const auto hi_plus = hn::Add(hn::Add(hn::LoadU(d, boxes.hi[c] + k), g_hi[c]), margin_v);
      meet = hn::And(meet, hn::And(hn::Le(lo, box_hi_plus[c]), hn::Le(box_lo[c], hi_plus)));
    }
    uint8_t bits[8] = {};
    hn::StoreMaskBits(d, meet, bits);
    meets |= uint32_t{bits[0]} << k;
  }
  return meets;
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace hs {

HWY_EXPORT(MeetingLanes);
HWY_EXPORT(GrownMeetingLanes);

uint32_t GrownBoxesMeeting(const BoxColumns& boxes, int count, const double (&grow_lo)[3],
                           const double (&grow_hi)[3], const AxisBox& box, double margin) {
  return HWY_DYNAMIC_DISPATCH(GrownMeetingLanes)(boxes, static_cast<size_t>(count), grow_lo,
                                                 grow_hi, box, margin);
}

void BucketBoxes::Meeting(std::span<const AxisBox> queries, std::span<uint32_t> out) const {
  const double* lo[3] = {lo_[0].data(), lo_[1].data(), lo_[2].data()};
  const double* hi_plus[3] = {hi_plus_margin_[0].data(), hi_plus_margin_[1].data(),
                              hi_plus_margin_[2].data()};
  HWY_DYNAMIC_DISPATCH(MeetingLanes)
  (lo, hi_plus, static_cast<size_t>(size_), margin_, queries.data(), queries.size(), out.data());
}

}  // namespace hs
#endif
