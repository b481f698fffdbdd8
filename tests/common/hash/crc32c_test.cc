#include "common/hash/crc32c.h"

#include <gtest/gtest.h>

#include <string>

namespace hs {
namespace {

// The check value of the CRC-32C catalogue entry, and RFC 3720's
// (iSCSI) test vectors: 32 zero bytes, 32 0xFF bytes, 0..31 ascending.
TEST(Crc32cTest, KnownValues) {
  EXPECT_EQ(Crc32c("123456789"), 0xE3069283u);
  EXPECT_EQ(Crc32c(std::string(32, '\0')), 0x8A9136AAu);
  EXPECT_EQ(Crc32c(std::string(32, '\xff')), 0x62A8AB43u);
  std::string ascending;
  for (int i = 0; i < 32; ++i) ascending.push_back(static_cast<char>(i));
  EXPECT_EQ(Crc32c(ascending), 0x46DD794Eu);
  EXPECT_EQ(Crc32c(""), 0u);
}

}  // namespace
}  // namespace hs
