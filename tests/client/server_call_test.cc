#include "client/server_call.h"

#include <gtest/gtest.h>

#include <chrono>
#include <sstream>

#include "client/exit_codes.h"
#include "haptics/v1/scene.pb.h"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

// Every status code maps to the exit status its class documents.
TEST(ServerCallTest, ExitCodesByClass) {
  using C = grpc::StatusCode;
  EXPECT_EQ(ExitCodeFor(grpc::Status::OK), kExitOk);
  for (C code : {C::UNAVAILABLE, C::DEADLINE_EXCEEDED}) {
    EXPECT_EQ(ExitCodeFor(grpc::Status(code, "")), kExitUnavailable) << code;
  }
  EXPECT_EQ(ExitCodeFor(grpc::Status(C::NOT_FOUND, "")), kExitNotFound);
  for (C code :
       {C::INVALID_ARGUMENT, C::ALREADY_EXISTS, C::FAILED_PRECONDITION, C::RESOURCE_EXHAUSTED,
        C::PERMISSION_DENIED, C::UNAUTHENTICATED, C::OUT_OF_RANGE, C::UNIMPLEMENTED}) {
    EXPECT_EQ(ExitCodeFor(grpc::Status(code, "")), kExitRefused) << code;
  }
  for (C code : {C::CANCELLED, C::UNKNOWN, C::ABORTED, C::INTERNAL, C::DATA_LOSS}) {
    EXPECT_EQ(ExitCodeFor(grpc::Status(code, "")), kExitFailure) << code;
  }
}

// Errors are one line on stderr: the command, the code's canonical name
// and the message; local failures the command and the message.
TEST(ServerCallTest, ReportsNameCommandCodeAndMessage) {
  std::ostringstream err;
  EXPECT_EQ(
      ReportRpcError("scenes", grpc::Status(grpc::StatusCode::NOT_FOUND, "no scene 'x'"), err),
      kExitNotFound);
  EXPECT_EQ(err.str(), "hapticctl scenes: NOT_FOUND: no scene 'x'\n");
  std::ostringstream local;
  EXPECT_EQ(ReportError("upload", absl::NotFoundError("cube.obj: cannot open"), local),
            kExitFailure);
  EXPECT_EQ(local.str(), "hapticctl upload: cube.obj: cannot open\n");
  EXPECT_EQ(StatusCodeName(grpc::StatusCode::DEADLINE_EXCEEDED), "DEADLINE_EXCEEDED");
}

// A context's deadline is the given seconds from now.
TEST(ServerCallTest, ContextDeadline) {
  const auto before = std::chrono::system_clock::now();
  const std::unique_ptr<grpc::ClientContext> context = ContextWithin(2.5);
  const auto after = std::chrono::system_clock::now();
  EXPECT_GE(context->deadline(), before + std::chrono::milliseconds(2500));
  EXPECT_LE(context->deadline(), after + std::chrono::milliseconds(2500));
}

// The connection flags fill the options; a timeout out of range and a
// missing file are command-line errors.
TEST(ServerCallTest, ConnectionOptionsFromFlags) {
  ConnectionOptions options;
  CLI::App app;
  AddConnectionOptions(app, options);
  app.parse("--server 10.0.0.2:7000 --timeout 0.5 --tls-server-name haptics.local", false);
  EXPECT_EQ(options.address, "10.0.0.2:7000");
  EXPECT_EQ(options.timeout_s, 0.5);
  EXPECT_EQ(options.tls_server_name, "haptics.local");
  EXPECT_EQ(options.tls_ca_file, "");
  CLI::App strict;
  ConnectionOptions other;
  AddConnectionOptions(strict, other);
  EXPECT_THROW(strict.parse("--timeout 0", false), CLI::ValidationError);
  CLI::App files;
  AddConnectionOptions(files, other);
  const std::string missing = (ScratchDir("server_call") / "ca.pem").string();
  EXPECT_THROW(files.parse("--tls-ca " + missing, false), CLI::ValidationError);
}

// A message as one JSON line with the proto's field names.
TEST(ServerCallTest, ProtoToJsonLineKeepsFieldNames) {
  haptics::v1::SceneSpec spec;
  spec.set_name("s");
  spec.set_step_s(0.002);
  EXPECT_EQ(ProtoToJsonLine(spec), R"({"name":"s","step_s":0.002})");
}

}  // namespace
}  // namespace hs::cli
