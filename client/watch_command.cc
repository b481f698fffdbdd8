#include "client/watch_command.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <iostream>
#include <mutex>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "client/frame_format.h"
#include "client/percentiles.h"
#include "client/sdk/grpc_error.h"
#include "client/sdk/watcher_impl.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

// What one second of frames held.
class SecondSummary {
 public:
  void Add(const pb::Frame& frame) {
    if (!started_) {
      // The counters are cumulative since the stream (drops) and the scene
      // (missed steps) began: the first second counts from its first frame.
      started_ = true;
      last_dropped_ = frame.dropped_frames();
      last_missed_ = frame.missed_steps();
    }
    if (frames_ == 0) {
      first_step_ = frame.step();
      start_dropped_ = last_dropped_;
      start_missed_ = last_missed_;
    }
    ++frames_;
    last_step_ = frame.step();
    last_dropped_ = frame.dropped_frames();
    last_missed_ = frame.missed_steps();
    step_ms_.push_back(1e-6 * static_cast<double>(frame.timings().step_ns()));
    // Clashes are counted since the scene began: the last frame's stand.
    clashes_ = SumClashes(frame);
    for (const pb::ToolState& tool : frame.tools()) {
      contacts_ = std::max(contacts_, tool.contacts_size());
      const pb::Vector3& f = tool.force_w_n();
      max_force_n_ =
          std::max(max_force_n_, std::sqrt(f.x() * f.x() + f.y() * f.y() + f.z() * f.z()));
    }
  }

  // Prints the second's line and starts the next one.
  void Flush(double elapsed_s, bool json, std::ostream& out) {
    const Percentiles step = Summarize(step_ms_);
    if (json) {
      nlohmann::ordered_json line = {{"elapsed_s", elapsed_s},
                                     {"frames", frames_},
                                     {"first_step", first_step_},
                                     {"last_step", last_step_},
                                     {"dropped_frames", last_dropped_ - start_dropped_},
                                     {"missed_steps", last_missed_ - start_missed_},
                                     {"max_contacts", contacts_},
                                     {"max_force_n", max_force_n_},
                                     {"tool_clashes", clashes_.count},
                                     {"tool_clash_s", clashes_.seconds},
                                     {"step_ms_p50", step.p50},
                                     {"step_ms_max", step.max}};
      out << line.dump() << "\n";
    } else {
      out << elapsed_s << " s: " << frames_ << " frames, steps " << first_step_ << ".."
          << last_step_ << ", dropped " << last_dropped_ - start_dropped_ << ", missed "
          << last_missed_ - start_missed_ << ", contacts <= " << contacts_
          << ", |force| <= " << max_force_n_ << " N, tool clashes " << clashes_.count << " ("
          << clashes_.seconds << " s), step p50 " << step.p50 << " ms, max " << step.max << " ms"
          << std::endl;
    }
    frames_ = 0;
    contacts_ = 0;
    max_force_n_ = 0;
    step_ms_.clear();
  }

  bool empty() const { return frames_ == 0; }

 private:
  bool started_ = false;
  int64_t frames_ = 0;
  int64_t first_step_ = 0;
  int64_t last_step_ = 0;
  uint64_t start_dropped_ = 0;
  uint64_t last_dropped_ = 0;
  int64_t start_missed_ = 0;
  int64_t last_missed_ = 0;
  int contacts_ = 0;
  double max_force_n_ = 0;
  ClashTotals clashes_;  // since the scene began, over every tool pair
  std::vector<double> step_ms_;
};

}  // namespace

int RunWatch(const WatchArgs& args, std::ostream& out, std::ostream& err) {
  // No --parts: every part, the local model too.
  haptics::WatchOptions options;
  options.poses = options.contacts = options.forces = options.local_model = args.parts.empty();
  options.open_timeout_s = args.server.timeout_s;
  for (const std::string& part : args.parts) {
    if (part == "poses") {
      options.poses = true;
    } else if (part == "contacts") {
      options.contacts = true;
    } else if (part == "forces") {
      options.forces = true;
    } else {
      return ReportError("watch", "unknown part '" + part + "' (poses, contacts, forces)", err);
    }
  }
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("watch", channel.status(), err);
  // Frames are printed on the watcher's thread; this one waits for the
  // stream's end, --frames or --duration.
  std::mutex mutex;
  std::condition_variable changed;
  bool done = false;
  int64_t frames = 0;
  SecondSummary second;
  const Clock::time_point start = Clock::now();
  Clock::time_point next_summary = start + std::chrono::seconds(1);
  auto on_message = [&](const pb::Frame& frame) {
    if (args.max_frames > 0 && frames >= args.max_frames) return;
    ++frames;
    if (args.summary) {
      second.Add(frame);
      if (Clock::now() >= next_summary) {
        second.Flush(std::chrono::duration<double>(Clock::now() - start).count(), args.json, out);
        next_summary += std::chrono::seconds(1);
      }
    } else {
      PrintFrame(frame, args.json, out);
    }
    if (args.max_frames > 0 && frames >= args.max_frames) {
      std::lock_guard lock(mutex);
      done = true;
      changed.notify_all();
    }
  };
  auto on_end = [&](const haptics::Error&) {
    std::lock_guard lock(mutex);
    done = true;
    changed.notify_all();
  };
  haptics::Result<std::unique_ptr<haptics::Watcher>> watcher = sdk::OpenWatcher(
      *std::move(channel), args.scene, options, {.on_message = on_message, .on_end = on_end});
  if (!watcher.ok()) return ReportRpcError("watch", sdk::ToGrpc(watcher.error()), err);
  {
    std::unique_lock lock(mutex);
    if (args.duration_s > 0) {
      changed.wait_until(lock,
                         start + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(args.duration_s)),
                         [&] { return done; });
    } else {
      changed.wait(lock, [&] { return done; });
    }
  }
  // Stopped here (--frames, --duration) it ends OK; else as the server ended it.
  (*watcher)->Close();
  const haptics::Error status = (*watcher)->status();
  watcher->reset();
  if (args.summary && !second.empty()) {
    second.Flush(std::chrono::duration<double>(Clock::now() - start).count(), args.json, out);
  }
  return status.ok() ? kExitOk : ReportRpcError("watch", sdk::ToGrpc(status), err);
}

void AddWatchCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<WatchArgs>();
  CLI::App* cmd =
      app.add_subcommand("watch", "Watch a scene as a viewer: every frame or a per-second summary");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("SCENE", args->scene, "Scene name")->required();
  cmd->add_option("--parts", args->parts, "poses, contacts, forces (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember({"poses", "contacts", "forces"}));
  cmd->add_flag("--summary", args->summary, "One line per second instead of one per frame");
  cmd->add_flag("--json", args->json, "JSON lines");
  cmd->add_option("--duration", args->duration_s, "Stop after this many seconds (0: never)")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--frames", args->max_frames, "Stop after this many frames (0: never)")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([args, &exit_code] { exit_code = RunWatch(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
