// Records of doubles loaded into SIMD lanes, a record a lane, for the
// batched kernels that test many faces or face pairs at once
// (face_test_batch.cc, common/contact/pair_nearness_batch.cc). On AVX2 and
// AVX3 the records are loaded in rows of four doubles and transposed in
// registers; elsewhere they are copied through a buffer a double at a time.
// (On this project's machine, an AMD EPYC, gathers a coordinate at a time
// took about as many instructions as the transpose but more time, and the
// copy more of both: its vector loads wait for the stores before them.)
// Compiled once per Highway target by each file that includes it after
// hwy/highway.h (Highway's per-target include guard below).

#if defined(HS_COLLISION_LANE_ROWS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HS_COLLISION_LANE_ROWS_INL_H_
#undef HS_COLLISION_LANE_ROWS_INL_H_
#else
#define HS_COLLISION_LANE_ROWS_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace hs {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Which of LoadColumns' `offsets` lands in lane `lane`: its own, but on
/// AVX3, whose block shuffles leave rows 2-3 and 4-5 swapped.
HWY_INLINE size_t RowOfLane(size_t lane) {
#if HWY_TARGET == HWY_AVX3
  constexpr size_t kRow[8] = {0, 1, 4, 5, 2, 3, 6, 7};
  return kRow[lane];
#else
  return lane;
#endif
}

/// The first 4 kGroups doubles of the records at `offsets` (in doubles
/// from `base`), record `offsets[RowOfLane(j)]` in lane j: column[k] holds
/// double k of each. Elsewhere than on AVX2 and AVX3 they go through `soa`
/// (4 kGroups rows of `stride`).
template <int kGroups, class D>
HWY_INLINE void LoadColumns(D d, const double* base, const int64_t* offsets, double* soa,
                            size_t stride, hn::Vec<D>* column) {
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3
  using V = hn::Vec<D>;
  (void)soa;
  (void)stride;
  for (int m = 0; m < kGroups; ++m) {
    // Row j: doubles 4m to 4m + 3 of record j (AVX2), of records j and
    // j + 4 in the two halves (AVX3).
    V row[4];
#if HWY_TARGET == HWY_AVX2
    for (int j = 0; j < 4; ++j) row[j] = hn::LoadU(d, base + offsets[j] + 4 * m);
#else
    const hn::Half<D> half;
    for (int j = 0; j < 4; ++j) {
      row[j] = hn::Combine(d, hn::LoadU(half, base + offsets[j + 4] + 4 * m),
                           hn::LoadU(half, base + offsets[j] + 4 * m));
    }
#endif
    // t0 = (r0[0] r1[0] r0[2] r1[2]), t1 = (r0[1] r1[1] r0[3] r1[3]); t2, t3
    // of r2 and r3 (in each half, on AVX3); then each column k gathers
    // element k of the rows.
    const V t0 = hn::InterleaveLower(d, row[0], row[1]);
    const V t1 = hn::InterleaveUpper(d, row[0], row[1]);
    const V t2 = hn::InterleaveLower(d, row[2], row[3]);
    const V t3 = hn::InterleaveUpper(d, row[2], row[3]);
#if HWY_TARGET == HWY_AVX2
    column[4 * m] = hn::ConcatLowerLower(d, t2, t0);
    column[4 * m + 1] = hn::ConcatLowerLower(d, t3, t1);
    column[4 * m + 2] = hn::ConcatUpperUpper(d, t2, t0);
    column[4 * m + 3] = hn::ConcatUpperUpper(d, t3, t1);
#else
    // 128-bit blocks 0 and 2 of t0, then of t2 (rows 0 1 4 5 2 3 6 7); 1
    // and 3 for the odd elements. Highway 1.0 has no such shuffle of two
    // vectors' blocks.
    constexpr int kEven = _MM_SHUFFLE(2, 0, 2, 0), kOdd = _MM_SHUFFLE(3, 1, 3, 1);
    column[4 * m] = V{_mm512_shuffle_f64x2(t0.raw, t2.raw, kEven)};
    column[4 * m + 1] = V{_mm512_shuffle_f64x2(t1.raw, t3.raw, kEven)};
    column[4 * m + 2] = V{_mm512_shuffle_f64x2(t0.raw, t2.raw, kOdd)};
    column[4 * m + 3] = V{_mm512_shuffle_f64x2(t1.raw, t3.raw, kOdd)};
#endif
  }
#else
  const size_t lanes = hn::Lanes(d);
  for (size_t j = 0; j < lanes; ++j) {
    const double* record = base + offsets[j];
    for (int k = 0; k < 4 * kGroups; ++k) soa[k * stride + j] = record[k];
  }
  for (int k = 0; k < 4 * kGroups; ++k) column[k] = hn::Load(d, soa + k * stride);
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace hs
HWY_AFTER_NAMESPACE();

#endif  // HS_COLLISION_LANE_ROWS_INL_H_
