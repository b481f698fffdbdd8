#include "common/net/address.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

// Loopback hosts in every spelling gRPC accepts count as this machine only.
TEST(AddressTest, LoopbackSpellingsAreLocal) {
  for (const char* address : {"127.0.0.1:50051", "127.1.2.3:0", "localhost:80", "[::1]:50051",
                              "ipv4:127.0.0.1:9", "ipv6:[::1]:9", "unix:/tmp/haptic.sock",
                              "unix-abstract:haptic"}) {
    EXPECT_TRUE(IsLoopbackAddress(address)) << address;
  }
}

// Wildcards, other interfaces and look-alike names reach other machines.
TEST(AddressTest, OtherAddressesAreRemote) {
  for (const char* address : {"0.0.0.0:50051", "[::]:50051", "10.0.0.5:1", "example.com:443",
                              "localhost.example.com:1", "128.0.0.1:1", "[::2]:1", "ipv4:10.0.0.1:9"}) {
    EXPECT_FALSE(IsLoopbackAddress(address)) << address;
  }
}

}  // namespace
}  // namespace hs
