// libFuzzer target: every request type of the API into a live in-process
// server. The first byte picks the method, the rest is the request's
// bytes, sent as they are (not parsed here): the server must answer every
// one with a status, never crash, and keep serving.

#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <future>
#include <string>

#include "common/api/scene_file.h"
#include "server/haptic_server.h"

namespace {

struct Fixture {
  Fixture() {
    hs::ServerOptions options;
    options.listen = "127.0.0.1:0";
    server = *hs::HapticServer::Start(options, metrics);
    haptics::v1::SceneSpec spec;
    spec.set_name("s");
    spec.set_step_s(0.01);  // a slow scene: the fuzzer's time goes to requests
    haptics::v1::SceneObject* box = spec.add_objects();
    box->set_name("box");
    box->set_kind(haptics::v1::OBJECT_KIND_TOOL);
    box->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_x(0.1);
    box->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_y(0.1);
    box->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m()->set_z(0.1);
    if (!server->registry().Create(spec, "").ok()) std::abort();
    channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(server->port()),
                                  grpc::InsecureChannelCredentials());
  }
  hs::Metrics metrics;
  std::unique_ptr<hs::HapticServer> server;
  std::shared_ptr<grpc::Channel> channel;
};

const char* const kUnary[] = {
    "/haptics.v1.SceneService/CreateScene",  "/haptics.v1.SceneService/GetScene",
    "/haptics.v1.SceneService/ListScenes",   "/haptics.v1.SceneService/DeleteScene",
    "/haptics.v1.SceneService/AddObject",    "/haptics.v1.SceneService/UpdateObject",
    "/haptics.v1.SceneService/RemoveObject", "/haptics.v1.SceneService/SetEffects",
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Fixture* fixture = new Fixture();  // lives for the whole run
  if (size < 1) return 0;
  grpc::GenericStub stub(fixture->channel);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  grpc::Slice slice(data + 1, size - 1);
  grpc::ByteBuffer request(&slice, 1), response;
  std::promise<grpc::Status> done;
  stub.UnaryCall(&context, kUnary[data[0] % (sizeof kUnary / sizeof *kUnary)], grpc::StubOptions(),
                 &request, &response, [&](grpc::Status s) { done.set_value(s); });
  const grpc::Status status = done.get_future().get();
  // A server that fell over answers UNAVAILABLE; one that stalled, DEADLINE_EXCEEDED.
  if (status.error_code() == grpc::StatusCode::UNAVAILABLE ||
      status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED) {
    std::abort();
  }
  return 0;
}
