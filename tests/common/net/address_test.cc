#include "common/net/address.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

// Loopback hosts in every spelling gRPC accepts count as this machine only.
TEST(AddressTest, LoopbackSpellingsAreLocal) {
  for (const char* address :
       {"127.0.0.1:50051", "127.1.2.3:0", "localhost:80", "[::1]:50051", "ipv4:127.0.0.1:9",
        "ipv6:[::1]:9", "unix:/tmp/haptic.sock", "unix-abstract:haptic"}) {
    EXPECT_TRUE(IsLoopbackAddress(address)) << address;
  }
}

// Wildcards, other interfaces and look-alike names reach other machines.
TEST(AddressTest, OtherAddressesAreRemote) {
  for (const char* address :
       {"0.0.0.0:50051", "[::]:50051", "10.0.0.5:1", "example.com:443", "localhost.example.com:1",
        "128.0.0.1:1", "[::2]:1", "ipv4:10.0.0.1:9"}) {
    EXPECT_FALSE(IsLoopbackAddress(address)) << address;
  }
}

// Host and port come apart at the last colon, IPv6 brackets dropped;
// anything without both, or with a port past 16 bits, is refused.
TEST(AddressTest, SplitsHostAndPort) {
  const std::optional<HostPort> v4 = SplitHostPort("127.0.0.1:50051");
  ASSERT_TRUE(v4);
  EXPECT_EQ(v4->host, "127.0.0.1");
  EXPECT_EQ(v4->port, 50051);
  const std::optional<HostPort> v6 = SplitHostPort("[::1]:0");
  ASSERT_TRUE(v6);
  EXPECT_EQ(v6->host, "::1");
  EXPECT_EQ(v6->port, 0);
  EXPECT_EQ(SplitHostPort("localhost:65535")->port, 65535);
  for (const char* bad : {"127.0.0.1", ":80", "host:", "host:65536", "host:8o", "host:123456"}) {
    EXPECT_FALSE(SplitHostPort(bad)) << bad;
  }
}

}  // namespace
}  // namespace hs
