#pragma once
// Values by id, each computed at most once between resets however often it
// is asked for: a vertex of a mesh is a corner of about six faces, so a
// query that places the faces of many pairs places each vertex once (the
// pair query's faces and vertices, common/collision/placed_faces.h; the
// sweep's and the contact locator's, common/contact).
// Reset forgets every value at once: an entry counts only while it bears
// the current generation, so nothing is cleared and the storage is kept
// from one query to the next.
//
// Written here: absl's and the standard library's maps hash every lookup
// and clear entry by entry; ids below a known bound need neither.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hs {

template <typename T>
class IdMemo {
 public:
  /// Forgets every value; ids from here on are below `size`.
  void Reset(size_t size) {
    if (values_.size() < size) {
      values_.resize(size);
      generations_.resize(size, 0);
    }
    if (++generation_ == 0) {  // wrapped: forget every generation
      std::fill(generations_.begin(), generations_.end(), 0);
      generation_ = 1;
    }
  }

  /// The values by id: those asked for since the last Reset are current,
  /// the others stale.
  const T* data() const { return values_.data(); }

  /// The value of `id` (in [0, size) of the last Reset) if it was asked
  /// for since then, else null.
  const T* Find(int id) const { return generations_[id] == generation_ ? &values_[id] : nullptr; }

  /// The value of `id` (in [0, size) of the last Reset): `compute()` the
  /// first time it is asked for since then, the same value after. The
  /// reference holds until the next Reset. Always inlined: the pair
  /// query's candidate loop asks for faces thousands of times a step, and
  /// a call there cost 3 % of Table 1 #4's coherent step.
  template <typename Compute>
  [[gnu::always_inline]] const T& Get(int id, Compute&& compute) {
    if (generations_[id] != generation_) {
      values_[id] = compute();
      generations_[id] = generation_;
    }
    return values_[id];
  }

 private:
  std::vector<T> values_;
  std::vector<uint32_t> generations_;
  uint32_t generation_ = 0;
};

}  // namespace hs
