// hapticctl sends its bearer token from --token-file or HAPTIC_TOKEN to a
// haptic-server that checks tokens.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <sstream>

#include "absl/strings/escaping.h"
#include "client/exit_codes.h"
#include "client/scenes_command.h"
#include "common/hash/sha256.h"
#include "server/haptic_server.h"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

class TokenServer {
 public:
  explicit TokenServer(const std::string& tokens_file) {
    ServerOptions options;
    options.listen = "127.0.0.1:0";
    options.tokens_file = tokens_file;
    absl::StatusOr<std::unique_ptr<HapticServer>> server = HapticServer::Start(options, metrics_);
    EXPECT_TRUE(server.ok()) << server.status();
    server_ = *std::move(server);
  }
  ~TokenServer() { server_->Shutdown(0.5); }
  std::string address() const { return "127.0.0.1:" + std::to_string(server_->port()); }

 private:
  Metrics metrics_;
  std::unique_ptr<HapticServer> server_;
};

// `hapticctl scenes list` against `server` with `token_file`; its exit status.
int List(const TokenServer& server, const std::string& token_file, std::string* err_text) {
  ScenesArgs args;
  args.action = "list";
  args.server.address = server.address();
  args.server.token_file = token_file;
  std::ostringstream out, err;
  const int code = RunScenes(args, out, err);
  *err_text = err.str();
  return code;
}

// The token goes with the call from a file (surrounding whitespace
// ignored) or from HAPTIC_TOKEN; without one, or with a wrong one, the
// server refuses (exit kExitRefused) and says why.
TEST(TokenTest, TokenFromFileOrEnvironment) {
  const std::filesystem::path dir = ScratchDir("tokens");
  Sha256 hash;
  hash.Update("s3cret");
  std::ofstream(dir / "tokens") << "sha256:" << absl::BytesToHexString(hash.Finish())
                                << " watch *\n";
  std::ofstream(dir / "good") << "  s3cret\n";
  std::ofstream(dir / "bad") << "guess\n";
  std::ofstream(dir / "empty") << "\n";
  TokenServer server((dir / "tokens").string());
  std::string err;
  unsetenv("HAPTIC_TOKEN");
  EXPECT_EQ(List(server, (dir / "good").string(), &err), kExitOk) << err;
  EXPECT_EQ(List(server, (dir / "bad").string(), &err), kExitRefused);
  EXPECT_NE(err.find("UNAUTHENTICATED: unknown token"), std::string::npos) << err;
  EXPECT_EQ(List(server, "", &err), kExitRefused);
  EXPECT_NE(err.find("UNAUTHENTICATED: this server needs a token"), std::string::npos) << err;
  EXPECT_EQ(List(server, (dir / "empty").string(), &err), kExitFailure);
  EXPECT_NE(err.find("holds no token"), std::string::npos) << err;
  setenv("HAPTIC_TOKEN", "s3cret", 1);
  EXPECT_EQ(List(server, "", &err), kExitOk) << err;
  unsetenv("HAPTIC_TOKEN");
}

}  // namespace
}  // namespace hs::cli
