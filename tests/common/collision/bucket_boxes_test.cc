#include "common/collision/bucket_boxes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "hwy/targets.h"

namespace hs {
namespace {

// The oracle: the comparisons BucketBoxes::Meeting names, one box at a
// time.
bool Meets(const AxisBox& box, const AxisBox& q, double margin) {
  bool meet = true;
  for (int d = 0; d < 3; ++d) {
    meet = meet && q.lo[d] <= box.hi[d] + margin && box.lo[d] <= q.hi[d] + margin;
  }
  return meet;
}

// Boxes on a coarse grid (so that faces touch, and boxes meet at exactly
// the margin), some with a NaN corner or infinite, some empty (lo > hi).
AxisBox RandomBox(std::mt19937& rng, double scale) {
  std::uniform_int_distribution<int> grid(-4, 4), kind(0, 19);
  AxisBox box;
  for (int d = 0; d < 3; ++d) {
    const double a = grid(rng) * scale, b = grid(rng) * scale;
    box.lo[d] = std::min(a, b);
    box.hi[d] = std::max(a, b);
  }
  switch (kind(rng)) {
    case 0:
      box.lo[grid(rng) & 1 ? 0 : 2] = std::nan("");
      break;
    case 1:
      box.hi[1] = std::numeric_limits<double>::infinity();
      break;
    case 2:
      std::swap(box.lo[0], box.hi[0]);
      break;
    default:
      break;
  }
  return box;
}

// Every size a bucket can have, every target this machine runs, margins 0
// and one grid step (so that boxes a step apart meet exactly at it).
TEST(BucketBoxesTest, MeetingGivesTheScalarComparisons) {
  std::mt19937 rng(41);
  int met = 0, missed = 0;
  for (const double scale : {1e-6, 1.0, 1e5}) {
    for (int size = 0; size <= BucketBoxes::kCapacity; ++size) {
      std::vector<AxisBox> boxes, queries;
      for (int k = 0; k < size; ++k) boxes.push_back(RandomBox(rng, scale));
      for (int i = 0; i < 7; ++i) queries.push_back(RandomBox(rng, scale));
      for (const double margin : {0.0, scale}) {
        BucketBoxes bucket;
        bucket.Start(margin);
        for (const AxisBox& box : boxes) bucket.Add(box.lo, box.hi);
        ASSERT_EQ(bucket.size(), size);
        for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
          hwy::SetSupportedTargetsForTest(target);
          SCOPED_TRACE(hwy::TargetName(target));
          std::vector<uint32_t> out(queries.size(), 0xdeadbeef);
          bucket.Meeting(queries, out);
          for (size_t i = 0; i < queries.size(); ++i) {
            for (int k = 0; k < BucketBoxes::kCapacity; ++k) {
              const bool expected = k < size && Meets(boxes[k], queries[i], margin);
              EXPECT_EQ((out[i] >> k) & 1, expected ? 1u : 0u)
                  << "size " << size << ", query " << i << ", box " << k;
              (expected ? met : missed) += k < size;
            }
          }
        }
        hwy::SetSupportedTargetsForTest(0);
      }
    }
  }
  EXPECT_GT(met, 1000);
  EXPECT_GT(missed, 1000);
}

// GrownBoxesMeeting against the comparisons it names, for every count a
// bucket can have, from an unaligned start, with boxes that would meet
// past the count (only read), on every target this machine runs.
TEST(BucketBoxesTest, GrownBoxesMeetingGivesTheScalarComparisons) {
  std::mt19937 rng(43);
  int met = 0, missed = 0;
  for (const double scale : {1e-6, 1.0, 1e5}) {
    for (int count = 0; count <= BucketBoxes::kCapacity; ++count) {
      const int first = count % 3;  // unaligned starts
      const int stored = first + count + BoxColumns::kReadPast;
      std::vector<AxisBox> boxes;
      std::array<std::vector<double>, 3> lo, hi;
      for (int k = 0; k < stored; ++k) {
        // Past the count: a box that meets everything.
        constexpr double kInf = std::numeric_limits<double>::infinity();
        boxes.push_back(k < first + count ? RandomBox(rng, scale)
                                          : AxisBox{{-kInf, -kInf, -kInf}, {kInf, kInf, kInf}});
        for (int d = 0; d < 3; ++d) {
          lo[d].push_back(boxes.back().lo[d]);
          hi[d].push_back(boxes.back().hi[d]);
        }
      }
      const BoxColumns columns{{lo[0].data() + first, lo[1].data() + first, lo[2].data() + first},
                               {hi[0].data() + first, hi[1].data() + first, hi[2].data() + first}};
      std::uniform_int_distribution<int> grid(0, 2);
      for (const double margin : {0.0, scale}) {
        const double grow_lo[3] = {-grid(rng) * scale, 0.0, -scale};
        const double grow_hi[3] = {0.0, grid(rng) * scale, scale};
        const AxisBox query = RandomBox(rng, scale);
        uint32_t expected = 0;
        for (int k = 0; k < count; ++k) {
          const AxisBox& box = boxes[first + k];
          bool meet = true;
          for (int d = 0; d < 3; ++d) {
            meet = meet && box.lo[d] + grow_lo[d] <= query.hi[d] + margin &&
                   query.lo[d] <= (box.hi[d] + grow_hi[d]) + margin;
          }
          expected |= uint32_t{meet} << k;
          (meet ? met : missed) += 1;
        }
        for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
          hwy::SetSupportedTargetsForTest(target);
          SCOPED_TRACE(hwy::TargetName(target));
          EXPECT_EQ(GrownBoxesMeeting(columns, count, grow_lo, grow_hi, query, margin), expected)
              << "count " << count << ", margin " << margin;
        }
        hwy::SetSupportedTargetsForTest(0);
      }
    }
  }
  EXPECT_GT(met, 50);
  EXPECT_GT(missed, 50);
}

// Keep leaves the boxes of the bits given, in order: Meeting then answers
// for them alone.
TEST(BucketBoxesTest, KeepLeavesTheBoxesGivenInOrder) {
  std::mt19937 rng(42);
  const double margin = 0.5;
  BucketBoxes bucket;
  bucket.Start(margin);
  std::vector<AxisBox> boxes;
  for (int k = 0; k < BucketBoxes::kCapacity; ++k) {
    boxes.push_back(RandomBox(rng, 1.0));
    bucket.Add(boxes.back().lo, boxes.back().hi);
  }
  const uint32_t kept = 0x8421f00du;
  bucket.Keep(bucket, kept);
  std::vector<AxisBox> kept_boxes;
  for (int k = 0; k < BucketBoxes::kCapacity; ++k) {
    if ((kept >> k) & 1) kept_boxes.push_back(boxes[k]);
  }
  ASSERT_EQ(bucket.size(), static_cast<int>(kept_boxes.size()));
  std::vector<AxisBox> queries;
  for (int i = 0; i < 20; ++i) queries.push_back(RandomBox(rng, 1.0));
  std::vector<uint32_t> out(queries.size());
  bucket.Meeting(queries, out);
  int met = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    uint32_t expected = 0;
    for (size_t k = 0; k < kept_boxes.size(); ++k) {
      expected |= uint32_t{Meets(kept_boxes[k], queries[i], margin)} << k;
    }
    EXPECT_EQ(out[i], expected) << "query " << i;
    met += std::popcount(expected);
  }
  EXPECT_GT(met, 10);
}

}  // namespace
}  // namespace hs
