#include "client/loadtest/loadtest.h"

#include <grpcpp/grpcpp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "absl/cleanup/cleanup.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "client/channel.h"
#include "client/device_path.h"
#include "client/frame_format.h"
#include "client/loadtest/echo_baseline.h"
#include "client/loadtest/process_cpu.h"
#include "client/loadtest/send_schedule.h"
#include "client/needs_args.h"
#include "common/api/proto_convert.h"
#include "common/net/address.h"
#include "common/sim/scene_options.h"
#include "haptics/v1/echo_service.grpc.pb.h"
#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

int64_t NowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
      .count();
}

absl::Status FromGrpc(const grpc::Status& status, const std::string& what) {
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()),
                      absl::StrCat("server: ", what, ": ", status.error_message()));
}

double ProcessCpuNow() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// Send times of one stream's messages (sequence 1..count) and the round
// trips of those answered. One writer thread marks sends, one reader
// thread marks answers.
class RoundTrips {
 public:
  explicit RoundTrips(size_t count) : sent_ns_(count, 0) { rtt_ms_.reserve(count); }

  void MarkSent(uint64_t sequence) {
    sent_ns_[sequence - 1] = NowNs();
    sent_.store(sequence, std::memory_order_release);
  }
  // Every sent message up to `sequence` not answered before is answered now.
  void MarkAnswered(uint64_t sequence) {
    const int64_t now = NowNs();
    sequence = std::min<uint64_t>(sequence, sent_.load(std::memory_order_acquire));
    uint64_t answered = answered_.load(std::memory_order_relaxed);
    for (; answered < sequence; ++answered) {
      rtt_ms_.push_back(1e-6 * static_cast<double>(now - sent_ns_[answered]));
    }
    answered_.store(answered, std::memory_order_release);
  }
  uint64_t sent() const { return sent_.load(std::memory_order_acquire); }
  uint64_t answered() const { return answered_.load(std::memory_order_acquire); }
  size_t count() const { return sent_ns_.size(); }
  std::vector<double>& rtt_ms() { return rtt_ms_; }

 private:
  std::vector<int64_t> sent_ns_;
  std::atomic<uint64_t> sent_{0};
  std::atomic<uint64_t> answered_{0};
  std::vector<double> rtt_ms_;
};

// Sends messages 1..count at the schedule's times through `write(sequence)`
// (false: the stream ended), then waits up to 2 s for their answers and
// closes the sending side with `done()`.
template <typename Write, typename Done>
void SendPaced(RoundTrips& trips, const SendSchedule& schedule, Write write, Done done) {
  for (uint64_t i = 0; i < trips.count(); ++i) {
    std::this_thread::sleep_until(schedule.At(i));
    trips.MarkSent(i + 1);
    if (!write(i + 1)) return;
  }
  const Clock::time_point give_up = Clock::now() + std::chrono::seconds(2);
  while (trips.answered() < trips.count() && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  done();
}

// What a stream's frames say, counted from the first frame of the window.
class FrameCounts {
 public:
  void Add(const pb::Frame& frame) {
    const bool first = frames_ == 0;
    ++frames_;
    step_.See(frame.step(), first);
    dropped_.See(static_cast<int64_t>(frame.dropped_frames()), first);
    missed_.See(frame.missed_steps(), first);
    missed_off_cpu_.See(frame.missed_steps_off_cpu(), first);
    const ClashTotals clashes = SumClashes(frame);
    clashes_.See(clashes.count, first);
    clash_s_.See(clashes.seconds, first);
  }
  void Fill(StreamReport& report, double window_s) const {
    report.frames = frames_;
    report.first_step = step_.first;
    report.last_step = step_.last;
    report.dropped_frames = dropped_.Grown();
    report.missed_steps = missed_.Grown();
    report.missed_steps_off_cpu = missed_off_cpu_.Grown();
    report.tool_clashes = clashes_.Grown();
    report.tool_clash_s = clash_s_.Grown();
    report.frames_per_s = static_cast<double>(frames_) / window_s;
  }
  int64_t frames() const { return frames_; }

 private:
  // A value of the frames at the window's first frame and at its latest.
  template <typename T>
  struct Span {
    T first = 0, last = 0;
    void See(T value, bool first_frame) {
      if (first_frame) first = value;
      last = value;
    }
    T Grown() const { return last - first; }
  };
  int64_t frames_ = 0;
  Span<int64_t> step_, dropped_, missed_, missed_off_cpu_, clashes_;
  Span<double> clash_s_;
};

// One device: an Interact stream driving one tool with a press motion.
class DeviceStream {
 public:
  // `frame_bytes` gets the size of a frame now and then, for the echo.
  DeviceStream(pb::SessionService::Stub& stub, const std::string& scene, const std::string& tool,
               const EffectSet& needs, std::vector<TimedPose> path,
               std::atomic<int64_t>& frame_bytes)
      : path_(std::move(path)), trips_(path_.size()), frame_bytes_out_(frame_bytes) {
    stream_ = stub.Interact(&context_);
    pb::InteractRequest open;
    open.mutable_open()->set_scene(scene);
    open.mutable_open()->set_tool(tool);
    SetNeeds(needs, *open.mutable_open());
    stream_->Write(open);
  }
  // A stream left open by an early return is cancelled, not waited for.
  ~DeviceStream() { context_.TryCancel(); }

  // Waits for the first frame: the device is attached. False when the stream ended.
  bool Attached() {
    pb::Frame frame;
    if (!stream_->Read(&frame)) return false;
    frame_bytes_out_.store(static_cast<int64_t>(frame.ByteSizeLong()));
    return true;
  }

  // Pose message `sequence` (1-based).
  pb::InteractRequest Request(uint64_t sequence) const {
    pb::InteractRequest request;
    pb::ToolPose* pose = request.mutable_pose();
    pose->set_sequence(sequence);
    pose->set_device_time_ns(NowNs());
    PoseToProto(path_[sequence - 1].X_WD, pose->mutable_pose());
    return request;
  }

  // Sends the path on `schedule` and reads frames until the stream ends.
  void Run(const SendSchedule& schedule, bool keep_step_times) {
    std::thread writer([&] {
      SendPaced(
          trips_, schedule, [&](uint64_t sequence) { return stream_->Write(Request(sequence)); },
          [&] { stream_->WritesDone(); });
    });
    pb::Frame frame;
    uint64_t applied = 0;  // the last pose sequence a frame applied
    while (stream_->Read(&frame)) {
      if (Clock::now() < schedule.start) continue;
      counts_.Add(frame);
      trips_.MarkAnswered(frame.last_pose_sequence());
      // Only steps that applied a new pose: in the echo's turns the devices
      // are still, and those steps run no stage.
      if (keep_step_times && frame.last_pose_sequence() > applied) {
        step_ms_.push_back(1e-6 * static_cast<double>(frame.timings().step_ns()));
      }
      applied = std::max(applied, frame.last_pose_sequence());
      if (counts_.frames() % 64 == 1) {
        frame_bytes_out_.store(static_cast<int64_t>(frame.ByteSizeLong()));
      }
    }
    writer.join();
    status_ = stream_->Finish();
  }

  StreamReport Report(double window_s) {
    StreamReport report;
    counts_.Fill(report, window_s);
    report.sent = static_cast<int64_t>(trips_.sent());
    report.answered = static_cast<int64_t>(trips_.answered());
    report.rtt_ms = Summarize(trips_.rtt_ms());
    return report;
  }

  // The status of a stream that ended before Run.
  grpc::Status Finish() { return stream_->Finish(); }
  const grpc::Status& status() const { return status_; }
  RoundTrips& trips() { return trips_; }
  std::vector<double>& step_ms() { return step_ms_; }

 private:
  std::vector<TimedPose> path_;
  RoundTrips trips_;
  std::atomic<int64_t>& frame_bytes_out_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<pb::InteractRequest, pb::Frame>> stream_;
  FrameCounts counts_;
  std::vector<double> step_ms_;
  grpc::Status status_;
};

// One echo stream with the devices' message sizes: requests as large as a
// pose message, answers as large as the devices' latest frames.
class EchoStream {
 public:
  EchoStream(pb::EchoService::Stub& stub, size_t count, int64_t request_bytes,
             const std::atomic<int64_t>& frame_bytes)
      : trips_(count), frame_bytes_(frame_bytes) {
    stream_ = stub.Echo(&context_);
    request_.set_reply_bytes(static_cast<uint32_t>(frame_bytes.load()));
    request_.set_sent_ns(NowNs());
    request_.set_sequence(count);
    // Pad so the message is as large as a device's pose message.
    const int64_t bare = static_cast<int64_t>(request_.ByteSizeLong()) + 2;
    request_.set_payload(std::string(std::max<int64_t>(0, request_bytes - bare), 'p'));
  }

  void Run(const SendSchedule& schedule) {
    std::thread writer([&] {
      SendPaced(
          trips_, schedule,
          [&](uint64_t sequence) {
            const int64_t reply_bytes = frame_bytes_.load();
            reply_bytes_ += reply_bytes;
            request_.set_reply_bytes(static_cast<uint32_t>(reply_bytes));
            request_.set_sequence(sequence);
            request_.set_sent_ns(NowNs());
            return stream_->Write(request_);
          },
          [&] { stream_->WritesDone(); });
    });
    pb::EchoMessage answer;
    while (stream_->Read(&answer)) {
      trips_.MarkAnswered(answer.sequence());
      ++frames_;
    }
    writer.join();
    status_ = stream_->Finish();
  }

  StreamReport Report(double window_s) {
    StreamReport report;
    report.sent = static_cast<int64_t>(trips_.sent());
    report.answered = static_cast<int64_t>(trips_.answered());
    report.frames = frames_;
    report.frames_per_s = static_cast<double>(frames_) / window_s;
    report.rtt_ms = Summarize(trips_.rtt_ms());
    return report;
  }
  const grpc::Status& status() const { return status_; }
  RoundTrips& trips() { return trips_; }
  // The mean size of the answers asked for.
  int64_t mean_reply_bytes() const {
    return trips_.sent() ? reply_bytes_ / static_cast<int64_t>(trips_.sent()) : 0;
  }

 private:
  RoundTrips trips_;
  const std::atomic<int64_t>& frame_bytes_;
  int64_t reply_bytes_ = 0;  // summed over the requests sent
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<pb::EchoMessage, pb::EchoMessage>> stream_;
  pb::EchoMessage request_;
  int64_t frames_ = 0;
  grpc::Status status_;
};

// One viewer: a Watch stream of every part until the scene is deleted or
// `stop` is called.
class ViewerStream {
 public:
  ViewerStream(pb::SessionService::Stub& stub, const std::string& scene) {
    pb::WatchRequest request;
    request.set_scene(scene);
    reader_ = stub.Watch(&context_, request);
  }
  void Run(Clock::time_point start) {
    pb::Frame frame;
    while (reader_->Read(&frame)) {
      if (Clock::now() >= start) counts_.Add(frame);
    }
    reader_->Finish();
  }
  void Stop() { context_.TryCancel(); }
  StreamReport Report(double window_s) const {
    StreamReport report;
    counts_.Fill(report, window_s);
    return report;
  }

 private:
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<pb::Frame>> reader_;
  FrameCounts counts_;
};

// Sums counts; pools round trips.
StreamReport Pool(const std::vector<StreamReport>& each, std::vector<double>& pooled_rtt_ms,
                  double window_s) {
  StreamReport total;
  for (const StreamReport& r : each) {
    total.sent += r.sent;
    total.answered += r.answered;
    total.frames += r.frames;
    total.dropped_frames += r.dropped_frames;
    total.missed_steps = std::max(total.missed_steps, r.missed_steps);
    total.missed_steps_off_cpu = std::max(total.missed_steps_off_cpu, r.missed_steps_off_cpu);
  }
  if (!each.empty()) {
    total.first_step = each.front().first_step;
    total.last_step = each.front().last_step;
  }
  total.frames_per_s = static_cast<double>(total.frames) / window_s;
  total.rtt_ms = Summarize(pooled_rtt_ms);
  return total;
}

// Runs `streams` (each on its own thread) until all are done, printing a
// progress line once a second.
template <typename Stream, typename RunOne>
void RunAll(std::vector<std::unique_ptr<Stream>>& streams, RunOne run_one, const char* phase,
            double duration_s, std::ostream* progress) {
  std::vector<std::thread> threads;
  std::atomic<size_t> done{0};
  for (auto& stream : streams) {
    threads.emplace_back([&, s = stream.get()] {
      run_one(*s);
      ++done;
    });
  }
  const Clock::time_point begin = Clock::now();
  Clock::time_point last_line = begin;
  while (done.load() < streams.size()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (progress == nullptr || Clock::now() - last_line < std::chrono::seconds(1)) continue;
    last_line = Clock::now();
    uint64_t sent = 0, answered = 0;
    for (auto& stream : streams) {
      sent += stream->trips().sent();
      answered += stream->trips().answered();
    }
    *progress << "loadtest: " << phase << " "
              << static_cast<int>(std::chrono::duration<double>(Clock::now() - begin).count())
              << "/" << duration_s << " s, " << streams.size() << " streams, " << sent << " sent, "
              << answered << " answered" << std::endl;
  }
  for (std::thread& t : threads) t.join();
}

// The devices' and the echo's turns, each this long: short enough that
// both meet the same noise of a shared machine, long enough that a turn's
// first round trips (streams waking up) weigh little.
constexpr double kTurnSeconds = 0.5;

// CPU seconds of the server (by pid, when known) and of this process,
// split by whose turn it was: a thread samples both at every slice
// boundary of `schedule` (or only at the start and at Stop without turns).
class TurnCpu {
 public:
  TurnCpu(int server_pid, const SendSchedule& schedule)
      : server_pid_(server_pid), schedule_(schedule) {
    thread_ = std::thread([this] { Sample(); });
  }
  ~TurnCpu() { Stop(); }

  // Takes the last sample now and stops.
  void Stop() {
    {
      std::lock_guard lock(mu_);
      stop_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  // Per turn (0: devices, 1: echo): wall, server and client seconds. The
  // server's are unknown (nullopt) without a pid or when a sample failed.
  double wall_s[2] = {0, 0};
  std::optional<double> server_s[2] = {0.0, 0.0};
  double client_s[2] = {0, 0};

 private:
  struct Reading {
    Clock::time_point at;
    std::optional<double> server;
    double client;
  };
  Reading Read() const {
    return {Clock::now(), server_pid_ ? ProcessCpuSeconds(server_pid_) : std::nullopt,
            ProcessCpuNow()};
  }

  void Sample() {
    std::unique_lock lock(mu_);
    cv_.wait_until(lock, schedule_.start, [this] { return stop_; });
    Reading last = Read();
    for (int slice = 0; !stop_; ++slice) {
      const Clock::time_point end =
          schedule_.slice_s > 0
              ? schedule_.start +
                    std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>((slice + 1) * schedule_.slice_s))
              : Clock::time_point::max();
      cv_.wait_until(lock, end, [this] { return stop_; });
      const Reading now = Read();
      const int turn = slice % 2;
      wall_s[turn] += std::chrono::duration<double>(now.at - last.at).count();
      client_s[turn] += now.client - last.client;
      if (server_s[turn] && now.server && last.server) {
        *server_s[turn] += *now.server - *last.server;
      } else {
        server_s[turn].reset();
      }
      last = now;
    }
  }

  const int server_pid_;
  const SendSchedule schedule_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace

pb::SceneSpec BuiltInLoadScene() {
  pb::SceneSpec spec;
  spec.set_name("probe on torus");
  spec.set_step_s(0.001);
  spec.set_force_clamp_n(10);
  pb::SceneObject* table = spec.add_objects();
  table->set_name("table");
  table->set_kind(pb::OBJECT_KIND_FIXED);
  VectorToProto(Vector3d(1, 1, 0.05),
                table->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m());
  VectorToProto(Vector3d(0, 0, -0.025), table->mutable_pose()->mutable_position_m());
  pb::SceneObject* organ = spec.add_objects();
  organ->set_name("organ");
  organ->set_kind(pb::OBJECT_KIND_FIXED);
  pb::Procedural::Torus* torus = organ->mutable_model()->mutable_procedural()->mutable_torus();
  torus->set_major_radius_m(0.1);
  torus->set_minor_radius_m(0.04);
  torus->set_major_segments(96);
  torus->set_minor_segments(48);
  VectorToProto(Vector3d(0, 0, 0.04), organ->mutable_pose()->mutable_position_m());
  pb::Material* material = organ->add_materials()->mutable_material();
  material->set_stiffness_n_per_m(400);
  material->set_damping_ns_per_m(0.5);
  material->set_static_friction(0.4);
  material->set_dynamic_friction(0.3);
  pb::SceneObject* probe = spec.add_objects();
  probe->set_name("probe");
  probe->set_kind(pb::OBJECT_KIND_TOOL);
  VectorToProto(Vector3d(0.02, 0.02, 0.02),
                probe->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m());
  VectorToProto(Vector3d(0.1, 0, 0.1), probe->mutable_pose()->mutable_position_m());
  return spec;
}

absl::StatusOr<pb::SceneSpec> LoadtestScene(const pb::SceneSpec& base, int clients,
                                            const std::string& name, bool tools_meet) {
  pb::SceneSpec spec = base;
  spec.set_name(name);
  spec.clear_objects();
  const pb::SceneObject* tool = nullptr;
  for (const pb::SceneObject& object : base.objects()) {
    if (object.kind() == pb::OBJECT_KIND_TOOL) {
      if (tool == nullptr) tool = &object;
    } else {
      *spec.add_objects() = object;
    }
  }
  if (tool == nullptr) return absl::InvalidArgumentError("the scene has no tool to copy");
  absl::StatusOr<Isometry3d> X_WT = PoseFromProto(tool->pose(), tool->name() + ".pose");
  if (!X_WT.ok()) return X_WT.status();
  const int groups = tools_meet ? (clients + 1) / 2 : clients;
  for (int i = 0; i < clients; ++i) {
    pb::SceneObject* copy = spec.add_objects();
    *copy = *tool;
    copy->set_name("tool-" + std::to_string(i));
    const int group = tools_meet ? i / 2 : i;
    const Isometry3d turn(Eigen::AngleAxisd(2 * M_PI * group / groups, Vector3d::UnitZ()));
    Isometry3d X_WC = *X_WT;
    if (tools_meet) X_WC.translation().y() += (i % 2 == 0 ? -0.5 : 0.5) * kMeetGapM;
    PoseToProto(turn * X_WC, copy->mutable_pose());
  }
  return spec;
}

std::vector<std::vector<TimedPose>> MeetingPaths(const std::vector<Isometry3d>& starts,
                                                 double rate_hz, double duration_s) {
  const size_t pairs = (starts.size() + 1) / 2;
  std::vector<std::vector<TimedPose>> paths;
  for (size_t i = 0; i < starts.size(); ++i) {
    MotionParams params;
    params.phase_s = static_cast<double>(i / 2) / static_cast<double>(pairs);
    const size_t partner = i ^ 1;
    if (partner < starts.size()) {
      const Vector3d apart = starts[partner].translation() - starts[i].translation();
      params.press_direction = apart.normalized();
      params.depth_m = 0.5 * apart.norm() + kMeetPastM;
    }
    paths.push_back(MotionPath(Motion::kPress, starts[i], rate_hz, duration_s, params));
  }
  return paths;
}

absl::Status CheckLoadtestOptions(const LoadtestOptions& options) {
  if (options.clients < 1 || options.clients > kMaxLoadClients) {
    return absl::InvalidArgumentError(absl::StrCat("--clients must be 1..", kMaxLoadClients));
  }
  if (options.viewers < 0 || options.viewers > kMaxLoadViewers) {
    return absl::InvalidArgumentError(absl::StrCat("--viewers must be 0..", kMaxLoadViewers));
  }
  if (!(options.duration_s > 0 && options.duration_s <= kMaxLoadSeconds)) {
    return absl::InvalidArgumentError(
        absl::StrCat("--duration must be in (0, ", kMaxLoadSeconds, "] seconds"));
  }
  if (!(options.rate_hz >= 1 && options.rate_hz <= kMaxLoadRateHz)) {
    return absl::InvalidArgumentError(absl::StrCat("--rate must be 1..", kMaxLoadRateHz, " Hz"));
  }
  if (options.step_s != 0 && !(options.step_s >= 1e-4 && options.step_s <= 1)) {
    return absl::InvalidArgumentError("--step-s must be in [0.0001, 1] seconds");
  }
  if (std::llround(options.duration_s * options.rate_hz) < 1) {
    return absl::InvalidArgumentError("--duration x --rate must make at least one pose");
  }
  if (!IsLoopbackAddress(options.server.address) && !options.allow_remote) {
    return absl::InvalidArgumentError(options.server.address +
                                      " is not on loopback: give --allow-remote to load it");
  }
  return absl::OkStatus();
}

absl::StatusOr<LoadReport> RunLoadtest(const LoadtestOptions& options) {
  if (absl::Status s = CheckLoadtestOptions(options); !s.ok()) return s;
  const bool loopback = IsLoopbackAddress(options.server.address);

  LoadReport report;
  report.clients = options.clients;
  report.viewers = options.viewers;
  report.rate_hz = options.rate_hz;
  report.needs = options.needs;
  report.duration_s = options.duration_s;
  report.load_average_1m = LoadAverage1m();
  report.scene = "loadtest-" + std::to_string(getpid());
  report.tools_meet = options.tools_meet;
  absl::StatusOr<pb::SceneSpec> spec =
      LoadtestScene(options.scene ? *options.scene : BuiltInLoadScene(), options.clients,
                    report.scene, options.tools_meet);
  if (!spec.ok()) return spec.status();
  if (options.step_s > 0) spec->set_step_s(options.step_s);
  report.step_s = spec->step_s() > 0 ? spec->step_s() : SceneOptions{}.step_s;

  absl::StatusOr<std::shared_ptr<grpc::Channel>> opened = MakeChannel(options.server);
  if (!opened.ok()) return opened.status();
  std::shared_ptr<grpc::Channel> channel = *std::move(opened);
  auto scenes = pb::SceneService::NewStub(channel);
  {
    pb::CreateSceneRequest request;
    *request.mutable_spec() = *spec;
    pb::SceneInfo info;
    const grpc::Status status =
        scenes->CreateScene(ContextWithin(options.server.timeout_s).get(), request, &info);
    if (!status.ok()) return FromGrpc(status, "CreateScene");
    report.triangles = info.triangles();
  }
  // The scene goes when the devices are done, or on any early return.
  absl::Cleanup delete_scene = [&] {
    pb::DeleteSceneRequest request;
    request.set_scene(report.scene);
    pb::DeleteSceneResponse response;
    scenes->DeleteScene(ContextWithin(options.server.timeout_s).get(), request, &response);
  };

  // Server CPU: the given pid, or the process listening on a loopback port.
  int server_pid = options.server_pid;
  if (server_pid == 0 && loopback) {
    const size_t colon = options.server.address.rfind(':');
    int port = 0;
    if (colon != std::string::npos &&
        absl::SimpleAtoi(options.server.address.substr(colon + 1), &port)) {
      server_pid = FindListeningPid(port).value_or(0);
    }
  }

  // Devices and viewers.
  auto sessions = pb::SessionService::NewStub(channel);
  std::atomic<int64_t> frame_bytes{0};
  std::vector<Isometry3d> starts;
  for (int i = 0; i < options.clients; ++i) {
    absl::StatusOr<Isometry3d> X_WT = PoseFromProto(
        spec->objects(spec->objects_size() - options.clients + i).pose(), "tool pose");
    if (!X_WT.ok()) return X_WT.status();
    starts.push_back(*X_WT);
  }
  std::vector<std::vector<TimedPose>> paths;
  if (options.tools_meet) {
    paths = MeetingPaths(starts, options.rate_hz, options.duration_s);
  } else {
    for (int i = 0; i < options.clients; ++i) {
      MotionParams params;
      params.phase_s = static_cast<double>(i) / options.clients;
      paths.push_back(
          MotionPath(Motion::kPress, starts[i], options.rate_hz, options.duration_s, params));
    }
  }
  std::vector<std::unique_ptr<DeviceStream>> devices;
  for (int i = 0; i < options.clients; ++i) {
    devices.push_back(std::make_unique<DeviceStream>(*sessions, report.scene,
                                                     "tool-" + std::to_string(i), options.needs,
                                                     std::move(paths[i]), frame_bytes));
  }
  for (auto& device : devices) {
    if (!device->Attached()) return FromGrpc(device->Finish(), "Interact");
  }
  const size_t count = devices.front()->trips().count();

  // The echo baseline: as many streams as devices, in-process, taking turns
  // with the devices.
  std::unique_ptr<EchoBaselineServer> echo_baseline;
  std::vector<std::unique_ptr<EchoStream>> echoes;
  if (options.echo) {
    absl::StatusOr<std::unique_ptr<EchoBaselineServer>> started = EchoBaselineServer::Start();
    if (!started.ok()) return started.status();
    echo_baseline = *std::move(started);
    auto echo_stub = pb::EchoService::NewStub(
        grpc::CreateChannel(echo_baseline->address(), grpc::InsecureChannelCredentials()));
    // A pose message's size depends on the pose: the mean over the path.
    constexpr uint64_t kSamples = 16;
    int64_t sampled = 0;
    for (uint64_t k = 0; k < kSamples && count > 0; ++k) {
      sampled += static_cast<int64_t>(
          devices.front()->Request(1 + k * (count - 1) / (kSamples - 1)).ByteSizeLong());
    }
    report.echo_request_bytes = sampled / static_cast<int64_t>(kSamples);
    for (int i = 0; i < options.clients; ++i) {
      echoes.push_back(
          std::make_unique<EchoStream>(*echo_stub, count, report.echo_request_bytes, frame_bytes));
    }
  }

  const SendSchedule device_turns{.start = Clock::now() + std::chrono::milliseconds(200),
                                  .rate_hz = options.rate_hz,
                                  .slice_s = options.echo ? kTurnSeconds : 0,
                                  .turn = 0};
  SendSchedule echo_turns = device_turns;
  echo_turns.turn = 1;
  std::vector<std::unique_ptr<ViewerStream>> viewers;
  std::vector<std::thread> viewer_threads;
  for (int i = 0; i < options.viewers; ++i) {
    viewers.push_back(std::make_unique<ViewerStream>(*sessions, report.scene));
    viewer_threads.emplace_back(
        [v = viewers.back().get(), start = device_turns.start] { v->Run(start); });
  }

  TurnCpu cpu(server_pid, device_turns);
  const std::optional<double> steal_before = MachineStealSeconds();
  std::thread echo_thread;
  if (options.echo) {
    echo_thread = std::thread([&] {
      RunAll(
          echoes, [&](EchoStream& e) { e.Run(echo_turns); }, "echo", 0, nullptr);
    });
  }
  RunAll(
      devices, [&](DeviceStream& d) { d.Run(device_turns, &d == devices.front().get()); },
      "devices", options.echo ? 2 * options.duration_s : options.duration_s, options.progress);
  if (echo_thread.joinable()) echo_thread.join();
  const double window_s = std::chrono::duration<double>(Clock::now() - device_turns.start).count();
  cpu.Stop();
  if (const std::optional<double> steal_after = MachineStealSeconds();
      steal_before && steal_after) {
    report.machine_steal_ms = 1e3 * (*steal_after - *steal_before);
  }
  // Percent of one core over a kind's turns; -1 when it had none.
  auto percent = [](double cpu_s, double wall_s) { return wall_s > 0 ? 100 * cpu_s / wall_s : -1; };
  report.client_cpu_percent = percent(cpu.client_s[0], cpu.wall_s[0]);
  if (cpu.server_s[0] && cpu.wall_s[0] > 0) {
    report.server_cpu_percent = percent(*cpu.server_s[0], cpu.wall_s[0]);
    report.server_cpu_source =
        absl::StrCat("/proc/", server_pid, "/stat",
                     server_pid == getpid() ? " (this process: server and load generator)" : "");
  } else {
    report.server_cpu_source = "unknown (give --server-pid for a server not on loopback)";
  }
  for (auto& viewer : viewers) viewer->Stop();
  for (std::thread& t : viewer_threads) t.join();
  std::move(delete_scene).Invoke();

  for (auto& device : devices) {
    if (!device->status().ok()) return FromGrpc(device->status(), "Interact");
  }
  std::vector<StreamReport> each;
  std::vector<double> pooled;
  for (auto& device : devices) {
    pooled.insert(pooled.end(), device->trips().rtt_ms().begin(), device->trips().rtt_ms().end());
    each.push_back(device->Report(window_s));
  }
  report.per_device = each;
  report.devices = Pool(each, pooled, window_s);
  report.step_ms = Summarize(devices.front()->step_ms());
  report.steps = each.front().frames > 0 ? each.front().last_step - each.front().first_step + 1 : 0;
  report.missed_steps = each.front().missed_steps;
  report.missed_steps_off_cpu = each.front().missed_steps_off_cpu;
  report.tool_clashes = each.front().tool_clashes;
  report.tool_clash_s = each.front().tool_clash_s;
  report.missed_fraction =
      static_cast<double>(report.missed_steps) /
      static_cast<double>(std::max<int64_t>(1, report.steps + report.missed_steps));
  std::vector<StreamReport> viewer_reports;
  for (auto& viewer : viewers) viewer_reports.push_back(viewer->Report(window_s));
  std::vector<double> no_rtt;
  report.viewers_total = Pool(viewer_reports, no_rtt, window_s);

  if (options.echo) {
    report.echo_run = true;
    report.echo_phase_cpu_percent = percent(cpu.client_s[1], cpu.wall_s[1]);
    std::vector<StreamReport> echo_each;
    std::vector<double> echo_pooled;
    int64_t reply_bytes = 0;
    for (auto& echo : echoes) {
      if (!echo->status().ok()) return FromGrpc(echo->status(), "Echo");
      echo_pooled.insert(echo_pooled.end(), echo->trips().rtt_ms().begin(),
                         echo->trips().rtt_ms().end());
      echo_each.push_back(echo->Report(cpu.wall_s[1]));
      reply_bytes += echo->mean_reply_bytes();
    }
    report.echo_reply_bytes = reply_bytes / options.clients;
    report.echo = Pool(echo_each, echo_pooled, cpu.wall_s[1]);
    if (report.echo.rtt_ms.p99 > 0) {
      report.p99_ratio = report.devices.rtt_ms.p99 / report.echo.rtt_ms.p99;
    }
    report.p99_budget_ms = 1.5 * report.echo.rtt_ms.p99 + report.step_ms.p99;
  }
  return report;
}

}  // namespace hs::cli
