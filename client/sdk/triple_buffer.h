#pragma once
// One writer hands the newest value to one reader, both wait-free: three
// slots, the writer filling one, the reader holding one, the third shared
// through one atomic word (its index and whether it is fresh). The writer
// never waits for the reader nor the reader for the writer; the reader
// gets the newest value written, older ones are overwritten.

#include <array>
#include <atomic>
#include <cstdint>

namespace hs::sdk {

template <typename T>
class TripleBuffer {
 public:
  /// The slot the writer fills; Publish hands it over.
  T& back() { return slots_[back_]; }
  /// Makes back() the newest value; back() is then another slot, holding
  /// an older value (copy over it whole).
  void Publish() {
    const uint32_t old = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel);
    back_ = old & kIndex;
  }

  /// Takes the newest value if one was published since the last Take:
  /// true, and front() is it. False: front() is what it was.
  bool Take() {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const uint32_t old = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndex;
    return true;
  }
  /// The reader's slot.
  const T& front() const { return slots_[front_]; }
  T& front() { return slots_[front_]; }

 private:
  static constexpr uint32_t kFresh = 4;
  static constexpr uint32_t kIndex = 3;
  std::array<T, 3> slots_{};
  uint32_t back_ = 0;
  uint32_t front_ = 1;
  std::atomic<uint32_t> middle_{2};
};

}  // namespace hs::sdk
