#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/escaping.h"
#include "common/hash/sha256.h"
#include "common/recording/recording_summary.h"
#include "common/recording/replay.h"
#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "server/cpu_affinity.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"
#include "tests/server/server_process.h"
#include "tests/server/test_server.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// A device stream on the demo's probe, its first frame read (`ok`).
struct ProbeDevice {
  explicit ProbeDevice(const std::shared_ptr<grpc::Channel>& channel)
      : stub(pb::SessionService::NewStub(channel)) {
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(20));
    stream = testing::OpenDevice(*stub, context, "probe on torus", "probe");
    ok = stream != nullptr && stream->Read(&frame);
  }
  std::unique_ptr<pb::SessionService::Stub> stub;
  grpc::ClientContext context;
  std::unique_ptr<testing::DeviceStream> stream;
  pb::Frame frame;
  bool ok = false;
};

// The binary serves the scene given with --scene on the port it picked,
// and on SIGTERM ends an open device stream with UNAVAILABLE after the
// frames it had and exits 0.
TEST(ServerMainTest, ServesSceneAndStopsGracefullyOnSigterm) {
  testing::ServerProcess server;
  ASSERT_GT(server.port(), 0);
  auto channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(server.port()),
                                     grpc::InsecureChannelCredentials());
  grpc::ClientContext get_context;
  get_context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  pb::GetSceneRequest get;
  get.set_scene("probe on torus");
  pb::SceneInfo info;
  ASSERT_TRUE(pb::SceneService::NewStub(channel)->GetScene(&get_context, get, &info).ok());
  EXPECT_EQ(info.spec().objects_size(), 3);

  ProbeDevice device(channel);
  ASSERT_TRUE(device.ok);

  std::thread reader([&] {
    while (device.stream->Read(&device.frame)) {
    }
  });
  EXPECT_EQ(server.StopWith(SIGTERM), 0);
  reader.join();
  EXPECT_EQ(device.stream->Finish().error_code(), grpc::StatusCode::UNAVAILABLE);
}

// The CPUs each thread of process `pid` may run on, as the kernel writes
// them (Cpus_allowed_list), one entry a thread.
std::vector<std::string> ThreadCpuLists(pid_t pid) {
  std::vector<std::string> lists;
  for (const auto& task :
       std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
    std::ifstream status(task.path() / "status");
    std::string line;
    while (std::getline(status, line)) {
      if (line.rfind("Cpus_allowed_list:", 0) == 0) {
        lists.push_back(line.substr(line.find_first_not_of(" \t", line.find(':') + 1)));
      }
    }
  }
  return lists;
}

// With --cpus, every thread of the server, gRPC's and the scene's among
// them, runs on that CPU only, and a device is served as without it.
TEST(ServerMainTest, CpusHoldEveryThread) {
  // On one CPU the threads would hold it whatever the flag did.
  if (AllowedCpus().size() < 2) GTEST_SKIP() << "this process may run on one CPU only";
  const std::string cpu = std::to_string(AllowedCpus().back());
  testing::ServerProcess server({"--cpus", cpu});
  ASSERT_GT(server.port(), 0) << server.startup();
  ProbeDevice device(grpc::CreateChannel("127.0.0.1:" + std::to_string(server.port()),
                                         grpc::InsecureChannelCredentials()));
  ASSERT_TRUE(device.ok);

  const std::vector<std::string> lists = ThreadCpuLists(server.pid());
  EXPECT_GE(lists.size(), 3u);  // main, the scene's stepping and frames threads, gRPC's
  for (const std::string& list : lists) EXPECT_EQ(list, cpu);
  device.context.TryCancel();
}

std::unique_ptr<pb::SceneService::Stub> SceneStub(int port) {
  return pb::SceneService::NewStub(
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials()));
}

grpc::Status GetScene(pb::SceneService::Stub& stub, const std::string& name, pb::SceneInfo& info) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  pb::GetSceneRequest get;
  get.set_scene(name);
  return stub.GetScene(&context, get, &info);
}

// With --state-dir, a scene created and then changed over the API is there
// again, as last changed, after the server is killed (SIGKILL: no chance
// to save anything) and started again on the same folder; the --scene
// file's scene is loaded as before. Without --state-dir the server says
// its scenes are lost when it stops.
TEST(ServerMainTest, ScenesSurviveAKill) {
  const std::string state = ScratchDir("state").string();
  {
    testing::ServerProcess server({"--state-dir", state});
    ASSERT_GT(server.port(), 0) << server.startup();
    auto stub = SceneStub(server.port());
    grpc::ClientContext create_context;
    pb::CreateSceneRequest create;
    *create.mutable_spec() = testing::SmallScene("kept", /*second_tool=*/false);
    pb::SceneInfo info;
    ASSERT_TRUE(stub->CreateScene(&create_context, create, &info).ok());
    grpc::ClientContext edit_context;
    pb::SetEffectsRequest edit;
    edit.set_scene("kept");
    edit.add_effects(pb::EFFECT_COLLISION);
    ASSERT_TRUE(stub->SetEffects(&edit_context, edit, &info).ok());
    server.StopWith(SIGKILL);
  }
  testing::ServerProcess again({"--state-dir", state});
  ASSERT_GT(again.port(), 0) << again.startup();
  auto stub = SceneStub(again.port());
  pb::SceneInfo info;
  ASSERT_TRUE(GetScene(*stub, "kept", info).ok());
  ASSERT_EQ(info.spec().effects_size(), 1);
  EXPECT_EQ(info.spec().effects(0), pb::EFFECT_COLLISION);
  EXPECT_EQ(info.spec().objects_size(), 2);
  EXPECT_TRUE(GetScene(*stub, "probe on torus", info).ok());

  testing::ServerProcess in_memory;
  EXPECT_NE(in_memory.startup().find("no --state-dir"), std::string::npos) << in_memory.startup();
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

// The recording files of scene `scene` in `dir`, oldest first.
std::vector<std::string> RecordingsOf(const std::string& dir, const std::string& scene) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().filename().string().starts_with(scene + "_")) {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Drives tool "probe" of `scene` down and up with a pose a millisecond,
// `poses` of them, reading frames as they come; returns the frames read.
// With `then` it runs once half the poses are sent (the stream stays open).
int DriveBurst(int port, const std::string& scene, int poses,
               const std::function<void()>& then = {}) {
  auto channel =
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials());
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(20));
  auto stream = pb::SessionService::NewStub(channel)->Interact(&context);
  pb::InteractRequest open;
  open.mutable_open()->set_scene(scene);
  open.mutable_open()->set_tool("probe");
  if (!stream->Write(open)) return 0;
  std::atomic<int> frames{0};
  std::thread reader([&] {
    pb::Frame frame;
    while (stream->Read(&frame)) ++frames;
  });
  for (int i = 0; i < poses; ++i) {
    pb::InteractRequest pose;
    pose.mutable_pose()->set_sequence(i + 1);
    const double z = 0.05 - 0.045 * std::sin(3.14159 * i / poses);  // into the table and out
    *pose.mutable_pose()->mutable_pose() = testing::PoseAt(0.001 * (i % 7), 0, z);
    if (!stream->Write(pose)) break;
    if (i == poses / 2 && then) then();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  context.TryCancel();
  reader.join();
  return frames;
}

// The crash test: a server with a state folder and a recording folder is
// killed (SIGKILL) during a burst of poses, during an upload and during
// an edit. Started again on the same folders, it has the scene and the
// model acknowledged before each kill, nothing of the cut upload, each
// recording's torn tail cut, and every recording of the scene replays
// bit for bit up to its last whole record.
TEST(ServerMainTest, StateAndRecordingsSurviveKills) {
  const std::string state = ScratchDir("crash_state").string();
  const std::string records = ScratchDir("crash_records").string();
  const std::vector<std::string> flags = {"--state-dir",      state, "--record-dir", records,
                                          "--record-sync-ms", "20"};
  const std::string cube = ReadFile(hs::TestDataDir() + "/cube.obj");
  ASSERT_FALSE(cube.empty());
  {  // 1. Killed during a burst of poses, after an upload and a create.
    testing::ServerProcess server(flags);
    ASSERT_GT(server.port(), 0) << server.startup();
    auto stub = SceneStub(server.port());
    pb::UploadModelResponse uploaded;
    ASSERT_TRUE(
        testing::UploadModel(*stub, "cube", "obj", cube, Sha256Of(cube), 1 << 20, &uploaded).ok());
    pb::CreateSceneRequest create;
    *create.mutable_spec() = testing::SmallScene("kept");
    pb::SceneObject* object = create.mutable_spec()->add_objects();
    object->set_name("cube");
    object->set_kind(pb::OBJECT_KIND_FIXED);
    object->mutable_model()->set_uploaded_model_id("cube.obj");
    *object->mutable_pose() = testing::PoseAt(0.3, 0, 0);
    pb::SceneInfo info;
    grpc::ClientContext create_context;
    ASSERT_TRUE(stub->CreateScene(&create_context, create, &info).ok());
    EXPECT_GT(DriveBurst(server.port(), "kept", 1500, [&] { server.Signal(SIGKILL); }), 0);
    server.StopWith(SIGKILL);
  }
  {  // 2. Killed during an upload: half its chunks sent.
    testing::ServerProcess server(flags);
    ASSERT_GT(server.port(), 0) << server.startup();
    auto stub = SceneStub(server.port());
    const std::string big(1 << 20, '#');
    pb::UploadModelResponse response;
    grpc::ClientContext context;
    auto writer = stub->UploadModel(&context, &response);
    pb::UploadModelChunk chunk;
    chunk.mutable_header()->set_name("cut");
    chunk.mutable_header()->set_format("obj");
    chunk.mutable_header()->set_size_bytes(2 * big.size());
    chunk.mutable_header()->set_sha256(std::string(32, 'x'));
    chunk.set_data(big);
    ASSERT_TRUE(writer->Write(chunk));
    server.StopWith(SIGKILL);
  }
  {  // 3. Killed during an edit sent in the middle of a burst, its reply not awaited.
    testing::ServerProcess server(flags);
    ASSERT_GT(server.port(), 0) << server.startup();
    auto stub = SceneStub(server.port());
    std::thread editor;
    DriveBurst(server.port(), "kept", 600, [&] {
      editor = std::thread([&] {
        grpc::ClientContext edit_context;
        edit_context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
        pb::SetEffectsRequest edit;
        edit.set_scene("kept");
        edit.add_effects(pb::EFFECT_COLLISION);
        pb::SceneInfo info;
        (void)stub->SetEffects(&edit_context, edit, &info);  // done or cut: either may be
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      server.Signal(SIGKILL);
    });
    editor.join();
    server.StopWith(SIGKILL);
  }
  // A crash that tore the last record of the newest recording: its bytes
  // cut short.
  const std::vector<std::string> recordings = RecordingsOf(records, "kept");
  ASSERT_EQ(recordings.size(), 3u);  // one per run
  std::ofstream(recordings.back(), std::ios::binary | std::ios::app)
      << std::string("\x40\0\0\0abc", 7);

  testing::ServerProcess again(flags);
  ASSERT_GT(again.port(), 0) << again.startup();
  EXPECT_NE(again.startup().find("cut short by a crash"), std::string::npos) << again.startup();
  auto stub = SceneStub(again.port());
  pb::SceneInfo info;
  ASSERT_TRUE(GetScene(*stub, "kept", info).ok());
  EXPECT_EQ(info.spec().objects_size(), 3);  // the uploaded cube's scene built again
  // The model acknowledged is kept (the same bytes again: the stored one);
  // nothing of the cut upload is left.
  pb::UploadModelResponse again_uploaded;
  ASSERT_TRUE(
      testing::UploadModel(*stub, "cube", "obj", cube, Sha256Of(cube), 1 << 20, &again_uploaded)
          .ok());
  EXPECT_EQ(again_uploaded.model_id(), "cube.obj");
  for (const auto& entry : std::filesystem::directory_iterator(state + "/models")) {
    EXPECT_FALSE(entry.path().filename().string().starts_with("cut")) << entry.path();
    EXPECT_FALSE(entry.path().filename().string().starts_with(".")) << entry.path();
  }
  for (size_t run = 0; run < recordings.size(); ++run) {
    const std::string& file = recordings[run];
    absl::StatusOr<RecordingSummary> summary = SummarizeRecording(file);
    ASSERT_TRUE(summary.ok()) << summary.status();
    EXPECT_FALSE(summary->ended) << file;                            // a crash ended it
    EXPECT_TRUE(summary->files.back().torn_reason.empty()) << file;  // cut at the start
    absl::StatusOr<ReplayReport> report = ReplayRecording(file, {});
    ASSERT_TRUE(report.ok()) << report.status();
    EXPECT_TRUE(report->all_identical())
        << file << ": step " << report->first_divergent_step << " " << report->first_divergent_field
        << " " << report->stopped_early;
    EXPECT_GT(report->steps_compared, 0) << file;
    if (run != 1) {  // the runs with a burst
      EXPECT_GT(summary->inputs, 100) << file;
    }
  }
}

// A state folder whose catalogue is not one (another file under its name)
// stops the start, naming the file: never a server on half a state.
TEST(ServerMainTest, ForeignCatalogueStopsTheStart) {
  const std::filesystem::path state = ScratchDir("foreign");
  std::ofstream(state / "scenes.db") << "not a database, though long enough to be read as one";
  testing::ServerProcess server({"--state-dir", state.string()});
  EXPECT_EQ(server.port(), 0);
  EXPECT_NE(server.startup().find((state / "scenes.db").string()), std::string::npos)
      << server.startup();
  EXPECT_EQ(server.StopWith(0), 1);
}

// The status of GetScene("probe on torus") with bearer token `token`.
grpc::StatusCode GetSceneAs(int port, const std::string& token) {
  auto channel =
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials());
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  context.AddMetadata("authorization", "Bearer " + token);
  pb::GetSceneRequest get;
  get.set_scene("probe on torus");
  pb::SceneInfo info;
  return pb::SceneService::NewStub(channel)->GetScene(&context, get, &info).error_code();
}

void WriteAdminToken(const std::string& path, const std::string& token) {
  Sha256 hash;
  hash.Update(token);
  std::ofstream(path) << "sha256:" << absl::BytesToHexString(hash.Finish()) << " admin *\n";
}

// With --tokens, the binary takes the tokens in the file, and on SIGHUP
// the file as it is then.
TEST(ServerMainTest, TokensFileIsReReadOnSighup) {
  const std::string tokens = (ScratchDir("sighup") / "tokens").string();
  WriteAdminToken(tokens, "first");
  testing::ServerProcess server({"--tokens", tokens});
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(GetSceneAs(server.port(), "first"), grpc::StatusCode::OK);
  EXPECT_EQ(GetSceneAs(server.port(), "second"), grpc::StatusCode::UNAUTHENTICATED);

  WriteAdminToken(tokens, "second");
  server.Signal(SIGHUP);
  EXPECT_NE(server.LineWith("SIGHUP: 1 tokens"), "");
  EXPECT_EQ(GetSceneAs(server.port(), "second"), grpc::StatusCode::OK);
  EXPECT_EQ(GetSceneAs(server.port(), "first"), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(server.StopWith(SIGTERM), 0);
}

}  // namespace
}  // namespace hs
