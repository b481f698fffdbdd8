#pragma once
// A fuzzer's input read as numbers: the libFuzzer targets of this folder
// build meshes, poses and faces from it.

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hs::fuzz {

/// Reads doubles and small integers off the input, zeros once it runs out.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  /// The next eight bytes as a double, whatever they hold (NaN, infinity,
  /// a subnormal).
  double Number() {
    double value = 0;
    if (size_ >= sizeof value) {
      std::memcpy(&value, data_, sizeof value);
      data_ += sizeof value;
      size_ -= sizeof value;
    }
    return value;
  }
  /// The next byte, in [0, below).
  int Small(int below) {
    if (size_ == 0) return 0;
    const int value = data_[0] % below;
    ++data_;
    --size_;
    return value;
  }

 private:
  const uint8_t* data_;
  size_t size_;
};

}  // namespace hs::fuzz
