#pragma once
// CRC32C (Castagnoli), the checksum of each recording record. Abseil
// 20220623 has no CRC32C; Boost.CRC computes it from the polynomial.

#include <cstdint>
#include <string_view>

#include <boost/crc.hpp>

namespace hs {

/// The CRC32C of `bytes` (reflected, initial and final XOR 0xFFFFFFFF; of
/// "123456789" it is 0xE3069283).
inline uint32_t Crc32c(std::string_view bytes) {
  boost::crc_optimal<32, 0x1EDC6F41, 0xFFFFFFFF, 0xFFFFFFFF, true, true> crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

}  // namespace hs
