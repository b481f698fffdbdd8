#include "client/loadtest/echo_baseline.h"

#include <grpcpp/grpcpp.h>

#include <chrono>

#include "haptics/v1/echo_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

// One stream: read a message, answer it, read the next. One operation at
// a time, so no locking.
class EchoReactor final : public grpc::ServerBidiReactor<pb::EchoMessage, pb::EchoMessage> {
 public:
  EchoReactor() { StartRead(&in_); }

  void OnReadDone(bool ok) override {
    if (!ok) {
      Finish(grpc::Status::OK);
      return;
    }
    out_.set_sequence(in_.sequence());
    out_.set_sent_ns(in_.sent_ns());
    out_.mutable_payload()->assign(std::min<uint32_t>(in_.reply_bytes(), 1 << 20), 'e');
    StartWrite(&out_);
  }
  void OnWriteDone(bool ok) override {
    if (!ok) {
      Finish(grpc::Status(grpc::StatusCode::CANCELLED, "write failed"));
      return;
    }
    StartRead(&in_);
  }
  void OnDone() override { delete this; }

 private:
  pb::EchoMessage in_;
  pb::EchoMessage out_;
};

class EchoService final : public pb::EchoService::CallbackService {
  grpc::ServerBidiReactor<pb::EchoMessage, pb::EchoMessage>* Echo(
      grpc::CallbackServerContext*) override {
    return new EchoReactor();
  }
};

}  // namespace

absl::StatusOr<std::unique_ptr<EchoBaselineServer>> EchoBaselineServer::Start() {
  std::unique_ptr<EchoBaselineServer> echo(new EchoBaselineServer());
  echo->service_ = std::make_unique<EchoService>();
  grpc::ServerBuilder builder;
  builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &echo->port_);
  builder.RegisterService(echo->service_.get());
  echo->server_ = builder.BuildAndStart();
  if (!echo->server_ || echo->port_ == 0) {
    return absl::UnavailableError("echo server: cannot listen on 127.0.0.1");
  }
  return echo;
}

EchoBaselineServer::~EchoBaselineServer() {
  server_->Shutdown(std::chrono::system_clock::now() + std::chrono::milliseconds(200));
}

std::string EchoBaselineServer::address() const { return "127.0.0.1:" + std::to_string(port_); }

}  // namespace hs::cli
