// MakeChannel's checks of its options. That the token reaches the server,
// and TLS with and without a client certificate, need a server: they are
// tests/e2e/token_test.cc and tls_test.cc.

#include "client/channel.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

// A plain channel needs no file.
TEST(ChannelTest, PlainChannel) {
  ConnectionOptions options;
  options.address = "127.0.0.1:1";
  const absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(options);
  ASSERT_TRUE(channel.ok()) << channel.status();
  EXPECT_NE(*channel, nullptr);
}

// A client certificate without its key or without a CA, a file that cannot
// be read and a token file holding no token are INVALID_ARGUMENT saying
// which.
TEST(ChannelTest, BadOptionsAreInvalidArgument) {
  const std::filesystem::path dir = ScratchDir("channel");
  const std::string pem = (dir / "some.pem").string();
  std::ofstream(pem) << "not really a certificate\n";
  const std::string blank = (dir / "blank_token").string();
  std::ofstream(blank) << " \n\t\n";
  const std::string missing = (dir / "missing.pem").string();
  struct Case {
    ConnectionOptions options;
    std::string says;
  };
  std::vector<Case> cases(5);
  cases[0].options.tls_cert_file = pem;
  cases[0].options.tls_key_file = pem;
  cases[0].says = "need --tls-ca";
  cases[1].options.tls_ca_file = pem;
  cases[1].options.tls_cert_file = pem;
  cases[1].says = "go together";
  cases[2].options.tls_ca_file = missing;
  cases[2].says = missing;
  cases[3].options.token_file = blank;
  cases[3].says = blank + " holds no token";
  cases[4].options.token_file = missing;
  cases[4].says = missing;
  for (const Case& c : cases) {
    const absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(c.options);
    EXPECT_EQ(channel.status().code(), absl::StatusCode::kInvalidArgument) << c.says;
    EXPECT_NE(channel.status().message().find(c.says), std::string::npos) << channel.status();
  }
}

}  // namespace
}  // namespace hs::cli
