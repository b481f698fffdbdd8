#include "client/loadtest/loadtest.h"

#include <grpcpp/grpcpp.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include "absl/cleanup/cleanup.h"
#include "absl/strings/str_cat.h"
#include "client/channel.h"
#include "client/loadtest/device_stream.h"
#include "client/loadtest/echo_baseline.h"
#include "client/loadtest/echo_stream.h"
#include "client/loadtest/process_cpu.h"
#include "client/loadtest/server_cpu.h"
#include "client/loadtest/start_contacts.h"
#include "client/loadtest/stream_runner.h"
#include "client/loadtest/turn_cpu.h"
#include "client/loadtest/viewer_stream.h"
#include "common/sim/scene_options.h"
#include "haptics/v1/echo_service.grpc.pb.h"
#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = SendSchedule::Clock;
using Devices = std::vector<std::unique_ptr<DeviceStream>>;

// The devices' and the echo's turns, each this long: short enough that
// both meet the same noise of a shared machine, long enough that a turn's
// first round trips (streams waking up) weigh little.
constexpr double kTurnSeconds = 0.5;

absl::Status FromGrpc(const grpc::Status& status, const std::string& what) {
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()),
                      absl::StrCat("server: ", what, ": ", status.error_message()));
}

// The report's settings, known before anything runs.
LoadReport Settings(const LoadtestOptions& options) {
  LoadReport report;
  report.clients = options.clients;
  report.viewers = options.viewers;
  report.rate_hz = options.rate_hz;
  report.needs = options.needs;
  report.duration_s = options.duration_s;
  report.load_average_1m = LoadAverage1m();
  report.scene = "loadtest-" + std::to_string(getpid());
  report.tools_meet = options.tools_meet;
  report.planes = options.planes;
  return report;
}

// The scene to create, named report.scene; sets report.step_s.
absl::StatusOr<pb::SceneSpec> RunSceneSpec(const LoadtestOptions& options, LoadReport& report) {
  absl::StatusOr<pb::SceneSpec> spec =
      LoadtestScene(options.scene ? *options.scene : BuiltInLoadScene(), options.clients,
                    report.scene, options.tools_meet);
  if (!spec.ok()) return spec.status();
  if (options.step_s > 0) spec->set_step_s(options.step_s);
  report.step_s = spec->step_s() > 0 ? spec->step_s() : SceneOptions{}.step_s;
  report.tools_touching_at_start = ToolPairsTouchingAtStart(*spec, options.scene_dir);
  return spec;
}

// Creates the scene; sets report.triangles.
absl::Status CreateScene(pb::SceneService::Stub& scenes, const pb::SceneSpec& spec,
                         double timeout_s, LoadReport& report) {
  pb::CreateSceneRequest request;
  *request.mutable_spec() = spec;
  pb::SceneInfo info;
  const grpc::Status status = scenes.CreateScene(ContextWithin(timeout_s).get(), request, &info);
  if (!status.ok()) return FromGrpc(status, "CreateScene");
  report.triangles = info.triangles();
  return absl::OkStatus();
}

void DeleteScene(pb::SceneService::Stub& scenes, const std::string& scene, double timeout_s) {
  pb::DeleteSceneRequest request;
  request.set_scene(scene);
  pb::DeleteSceneResponse response;
  scenes.DeleteScene(ContextWithin(timeout_s).get(), request, &response);
}

// Opens every device's stream on its tool of `spec` and waits until each
// is attached.
absl::StatusOr<Devices> OpenDevices(pb::SessionService::Stub& sessions, const pb::SceneSpec& spec,
                                    const LoadtestOptions& options,
                                    std::atomic<int64_t>& frame_bytes) {
  absl::StatusOr<std::vector<std::vector<TimedPose>>> paths =
      DevicePaths(spec, options.clients, options.tools_meet, options.rate_hz, options.duration_s);
  if (!paths.ok()) return paths.status();
  Devices devices;
  for (int i = 0; i < options.clients; ++i) {
    const DeviceOpen open{.scene = spec.name(),
                          .tool = "tool-" + std::to_string(i),
                          .needs = options.needs,
                          .frame_rate_hz = options.frame_rate_hz,
                          .surface_only = !options.planes};
    devices.push_back(
        std::make_unique<DeviceStream>(sessions, open, std::move((*paths)[i]), frame_bytes));
  }
  for (auto& device : devices) {
    if (!device->Attached()) return FromGrpc(device->Finish(), "Interact");
  }
  return devices;
}

// The echo baseline: an in-process echo server and as many streams as
// devices, each for `count` messages of `request_bytes`.
struct Echo {
  std::unique_ptr<EchoBaselineServer> server;
  std::unique_ptr<pb::EchoService::Stub> stub{};
  std::vector<std::unique_ptr<EchoStream>> streams{};
};

absl::StatusOr<Echo> StartEcho(int clients, size_t count, int64_t request_bytes,
                               const std::atomic<int64_t>& frame_bytes) {
  absl::StatusOr<std::unique_ptr<EchoBaselineServer>> started = EchoBaselineServer::Start();
  if (!started.ok()) return started.status();
  Echo echo{.server = *std::move(started)};
  echo.stub = pb::EchoService::NewStub(
      grpc::CreateChannel(echo.server->address(), grpc::InsecureChannelCredentials()));
  for (int i = 0; i < clients; ++i) {
    echo.streams.push_back(
        std::make_unique<EchoStream>(*echo.stub, count, request_bytes, frame_bytes));
  }
  return echo;
}

// What the run measured.
struct Measured {
  // From the devices' schedule's start to their end.
  double window_s = 0;
  TurnTotals cpu;
  double machine_steal_ms = -1;
  StreamReport viewers;
};

// Runs the devices, and the echo (when not null) in turns with them, with
// the viewers watching the scene, and measures.
Measured Drive(const LoadtestOptions& options, pb::SessionService::Stub& sessions,
               const std::string& scene, Devices& devices, Echo* echo,
               const ServerCpuSource& server_cpu) {
  const SendSchedule device_turns{.start = Clock::now() + std::chrono::milliseconds(200),
                                  .rate_hz = options.rate_hz,
                                  .slice_s = echo ? kTurnSeconds : 0,
                                  .turn = 0};
  SendSchedule echo_turns = device_turns;
  echo_turns.turn = 1;
  std::vector<std::unique_ptr<ViewerStream>> viewers;
  std::vector<std::thread> viewer_threads;
  for (int i = 0; i < options.viewers; ++i) {
    viewers.push_back(std::make_unique<ViewerStream>(sessions, scene));
    viewer_threads.emplace_back(
        [v = viewers.back().get(), start = device_turns.start] { v->Run(start); });
  }
  std::vector<std::function<void()>> device_runs, echo_runs;
  std::vector<const RoundTrips*> device_trips;
  for (auto& device : devices) {
    device_runs.push_back(
        [&, d = device.get()] { d->Run(device_turns, d == devices.front().get()); });
    device_trips.push_back(&device->trips());
  }
  if (echo) {
    for (auto& stream : echo->streams) {
      echo_runs.push_back([&, e = stream.get()] { e->Run(echo_turns); });
    }
  }

  Measured measured;
  TurnCpu cpu({.server = server_cpu.read, .client = OwnCpuSeconds}, device_turns);
  const std::optional<double> steal_before = MachineStealSeconds();
  std::thread echo_thread;
  if (echo) echo_thread = std::thread([&] { RunStreams(echo_runs, {}, "echo", 0, nullptr); });
  RunStreams(device_runs, device_trips, "devices",
             echo ? 2 * options.duration_s : options.duration_s, options.progress);
  if (echo_thread.joinable()) echo_thread.join();
  measured.window_s = std::chrono::duration<double>(Clock::now() - device_turns.start).count();
  measured.cpu = cpu.Stop();
  if (const std::optional<double> steal_after = MachineStealSeconds();
      steal_before && steal_after) {
    measured.machine_steal_ms = 1e3 * (*steal_after - *steal_before);
  }
  for (auto& viewer : viewers) viewer->Stop();
  for (std::thread& t : viewer_threads) t.join();
  std::vector<StreamReport> viewer_reports;
  for (auto& viewer : viewers) viewer_reports.push_back(viewer->Report(measured.window_s));
  std::vector<double> no_rtt;
  measured.viewers = Pool(viewer_reports, no_rtt, measured.window_s);
  return measured;
}

// The devices' figures, or the first failed stream's status.
absl::Status CollectDevices(Devices& devices, double window_s, LoadReport& report) {
  std::vector<StreamReport> each;
  std::vector<double> pooled;
  for (auto& device : devices) {
    if (!device->status().ok()) return FromGrpc(device->status(), "Interact");
    pooled.insert(pooled.end(), device->trips().rtt_ms().begin(), device->trips().rtt_ms().end());
    each.push_back(device->Report(window_s));
  }
  SetDeviceFigures(std::move(each), pooled, devices.front()->step_ms(), window_s, report);
  return absl::OkStatus();
}

// The echo's figures over its turns, or the first failed stream's status.
absl::Status CollectEcho(Echo& echo, double window_s, LoadReport& report) {
  std::vector<StreamReport> each;
  std::vector<double> pooled;
  std::vector<int64_t> reply_bytes;
  for (auto& stream : echo.streams) {
    if (!stream->status().ok()) return FromGrpc(stream->status(), "Echo");
    pooled.insert(pooled.end(), stream->trips().rtt_ms().begin(), stream->trips().rtt_ms().end());
    each.push_back(stream->Report(window_s));
    reply_bytes.push_back(stream->mean_reply_bytes());
  }
  SetEchoFigures(each, pooled, reply_bytes, window_s, report);
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<LoadReport> RunLoadtest(const LoadtestOptions& options) {
  if (absl::Status s = CheckLoadtestOptions(options); !s.ok()) return s;
  LoadReport report = Settings(options);
  absl::StatusOr<pb::SceneSpec> spec = RunSceneSpec(options, report);
  if (!spec.ok()) return spec.status();
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(options.server);
  if (!channel.ok()) return channel.status();
  auto scenes = pb::SceneService::NewStub(*channel);
  if (absl::Status s = CreateScene(*scenes, *spec, options.server.timeout_s, report); !s.ok()) {
    return s;
  }
  // The scene goes when the devices are done, or on any early return.
  absl::Cleanup delete_scene = [&] {
    DeleteScene(*scenes, report.scene, options.server.timeout_s);
  };
  const ServerCpuSource server_cpu = FindServerCpuSource(options);
  auto sessions = pb::SessionService::NewStub(*channel);
  std::atomic<int64_t> frame_bytes{0};
  absl::StatusOr<Devices> devices = OpenDevices(*sessions, *spec, options, frame_bytes);
  if (!devices.ok()) return devices.status();
  std::optional<Echo> echo;
  if (options.echo) {
    report.echo_request_bytes = devices->front()->MeanRequestBytes();
    absl::StatusOr<Echo> started = StartEcho(options.clients, devices->front()->trips().count(),
                                             report.echo_request_bytes, frame_bytes);
    if (!started.ok()) return started.status();
    echo = *std::move(started);
  }
  const Measured measured =
      Drive(options, *sessions, report.scene, *devices, echo ? &*echo : nullptr, server_cpu);
  std::move(delete_scene).Invoke();
  report.machine_steal_ms = measured.machine_steal_ms;
  report.viewers_total = measured.viewers;
  SetCpuFigures(measured.cpu, server_cpu.description, options.echo, report);
  if (absl::Status s = CollectDevices(*devices, measured.window_s, report); !s.ok()) return s;
  if (echo) {
    if (absl::Status s = CollectEcho(*echo, measured.cpu.wall_s[1], report); !s.ok()) return s;
  }
  return report;
}

}  // namespace hs::cli
