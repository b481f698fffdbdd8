#include "server/server_flags.h"

#include <algorithm>
#include <cstdint>
#include <thread>

#include "CLI/CLI.hpp"
#include "absl/strings/numbers.h"
#include "server/cpu_affinity.h"

namespace hs {
namespace {

// The server's own options: where it listens, who may call, where it keeps
// state and recordings.
void AddServingFlags(CLI::App& app, ServerFlags& flags) {
  ServerOptions& options = flags.server;
  app.add_option("--listen", options.listen, "host:port to serve gRPC on (port 0: any free)")
      ->capture_default_str();
  app.add_option("--tls-cert", options.tls.cert_file, "PEM certificate chain: serve over TLS")
      ->check(CLI::ExistingFile);
  app.add_option("--tls-key", options.tls.key_file, "PEM private key of --tls-cert")
      ->check(CLI::ExistingFile);
  app.add_option("--tls-client-ca", options.tls.client_ca_file,
                 "PEM CA certificates: clients must present a certificate they signed (mutual TLS)")
      ->check(CLI::ExistingFile);
  app.add_flag("--insecure-listen", options.insecure_listen,
               "Allow --listen on an address other machines reach without TLS");
  app.add_option("--tokens", options.tokens_file,
                 "Tokens and their roles, one 'sha256:<hex> ROLE SCENE_PATTERN' a line; re-read "
                 "on SIGHUP. Without it any client may do anything")
      ->check(CLI::ExistingFile);
  app.add_option("--scene", flags.scene_files, "Scene file to load at start (repeatable)")
      ->check(CLI::ExistingFile);
  app.add_option("--metrics", flags.metrics_address, "host:port to serve Prometheus /metrics on");
  app.add_option("--model-dir", options.model_dir,
                 "Folder for uploaded models (default: STATE_DIR/models, else a temporary folder)");
  app.add_option("--state-dir", options.state_dir,
                 "Keep scenes created or changed over the API (scenes.db, SQLite) and uploaded "
                 "models (models/) in this folder across restarts; without it they live in "
                 "memory");
}

// --record-*. The two word-valued flags land in `frames` and `scenes`,
// turned into RecordingOptions once parsed.
void AddRecordingFlags(CLI::App& app, RecordingOptions& recording, std::string& frames,
                       std::string& scenes) {
  app.add_option("--record-dir", recording.dir,
                 "Record each scene's session (spec, edits, device poses, streams, frames) into "
                 "this folder, one file per session (docs/recording.md)");
  app.add_option("--record-frames", frames,
                 "What recordings keep of each frame: 'full', or 'digest' (its SHA-256)")
      ->check(CLI::IsMember({"full", "digest"}))
      ->capture_default_str();
  app.add_option("--record-scenes", scenes,
                 "Which scenes --record-dir records: 'all', or 'requested' (those whose spec "
                 "sets record)")
      ->check(CLI::IsMember({"all", "requested"}))
      ->capture_default_str();
  app.add_option("--record-sync-ms", recording.sync_ms,
                 "Longest a recorded record waits before it is synced to the disk, ms")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  app.add_option("--record-max-bytes", recording.max_file_bytes,
                 "A recording file past this size rolls over to the session's next part")
      ->check(CLI::Range(int64_t{1} << 16, int64_t{1} << 40))
      ->capture_default_str();
}

void AddLimitFlags(CLI::App& app, ServerLimits& limits) {
  app.add_option("--max-scenes", limits.max_scenes)->capture_default_str();
  app.add_option("--max-clients", limits.max_clients)->capture_default_str();
  app.add_option("--max-objects", limits.max_objects_per_scene)->capture_default_str();
  app.add_option("--max-triangles", limits.max_triangles_per_scene)->capture_default_str();
  app.add_option("--max-spec-bytes", limits.max_spec_bytes,
                 "Largest scene spec, serialized, bytes (it comes back in every SceneInfo)")
      ->capture_default_str();
  app.add_option("--max-streams-per-caller", limits.per_caller.streams,
                 "Open Interact and Watch streams per caller (token, or peer on an open server)")
      ->capture_default_str();
  app.add_option("--max-uploads-per-caller", limits.per_caller.uploads_in_flight,
                 "Uploads in progress per caller")
      ->capture_default_str();
  app.add_option("--max-models-per-caller", limits.per_caller.models,
                 "Stored models per caller (until deleted)")
      ->capture_default_str();
  app.add_option("--max-scenes-per-caller", limits.per_caller.scenes,
                 "Scenes per caller (until deleted)")
      ->capture_default_str();
  app.add_option("--max-vertex-moves", limits.max_vertex_moves_per_request,
                 "Vertex moves in one UpdateObject")
      ->capture_default_str();
}

// One thread a scene per CPU the server runs on, up to 4: a step rarely
// has more tools than that busy.
int DefaultThreadsPerScene(size_t cpus) { return static_cast<int>(std::clamp<size_t>(cpus, 1, 4)); }

// The CPUs the process may run on, or the machine's when the system does
// not say.
size_t UsableCpuCount() {
  const size_t allowed = AllowedCpus().size();
  return allowed > 0 ? allowed : std::thread::hardware_concurrency();
}

// How scenes are stepped: CPUs, threads, scheduling, silent devices.
void AddSteppingFlags(CLI::App& app, ServerFlags& flags, std::string& cpus) {
  ServerLimits& limits = flags.server.limits;
  app.add_option("--cpus", cpus,
                 "Run the server on these CPUs only, numbers and ranges as taskset -c writes them "
                 "(0,2-3): threads that wake one another on one CPU cost less than across CPUs. "
                 "Default: every CPU it may use");
  limits.threads_per_scene = DefaultThreadsPerScene(UsableCpuCount());
  app.add_option("--threads-per-scene", limits.threads_per_scene,
                 "Threads that step one scene's tools at once (default: one per CPU the server "
                 "runs on, up to 4)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--realtime-priority", limits.realtime_priority,
                 "SCHED_FIFO priority (1-99) of the threads that step scenes, so that a busy "
                 "machine delays no step; needs root or CAP_SYS_NICE, checked at start. 0: the "
                 "default scheduler. A scene whose step outlasts its period then holds its cores")
      ->check(CLI::Range(0, 99))
      ->capture_default_str();
  app.add_option("--device-timeout-s", limits.device_timeout_s,
                 "A device that sends no pose for this long is ended (DEADLINE_EXCEEDED) and "
                 "its tool released where it was; 0: never")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
}

void AddAgonesFlags(CLI::App& app, AgonesOptions& agones) {
  app.add_option("--agones-health-interval-s", agones.health_interval_s,
                 "On Agones (AGONES_SDK_HTTP_PORT set): seconds between health pings")
      ->check(CLI::Range(0.1, 300.0))
      ->capture_default_str();
  app.add_option("--agones-idle-shutdown-s", agones.idle_shutdown_s,
                 "On Agones: ask to be shut down once the last client has left and this many "
                 "seconds passed")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
}

// AGONES_SDK_HTTP_PORT, set by Agones in a game server's container: the
// SDK's port, or 0 when unset or empty. False when it is set to no port.
bool ReadAgonesPort(const EnvironmentReader& getenv, int& port, std::ostream& err) {
  const char* value = getenv("AGONES_SDK_HTTP_PORT");
  if (value == nullptr || *value == 0) return true;
  if (!absl::SimpleAtoi(value, &port) || port < 1 || port > 65535) {
    err << "haptic-server: AGONES_SDK_HTTP_PORT='" << value << "' is not a port\n";
    return false;
  }
  return true;
}

// --cpus, when given: CPUs this process may run on, and then the threads'
// default. False, with a message, when they are not.
bool ReadCpus(const CLI::App& app, const std::string& text, ServerFlags& flags, std::ostream& err) {
  if (app.count("--cpus") == 0) return true;
  absl::StatusOr<std::vector<int>> cpus = ParseCpuList(text);
  absl::Status allowed = cpus.ok() ? CheckCpusAllowed(*cpus) : cpus.status();
  if (!allowed.ok()) {
    err << "haptic-server: --cpus: " << allowed.message() << "\n";
    return false;
  }
  flags.cpus = *std::move(cpus);
  int& threads = flags.server.limits.threads_per_scene;
  if (app.count("--threads-per-scene") == 0) {
    threads = DefaultThreadsPerScene(flags.cpus.size());
  } else if (static_cast<size_t>(threads) > flags.cpus.size()) {
    err << "haptic-server: warning: --threads-per-scene " << threads << " on " << flags.cpus.size()
        << " CPU(s) of --cpus: the threads past one a CPU only add wake-ups\n";
  }
  return true;
}

}  // namespace

ParsedServerFlags ParseServerFlags(int argc, const char* const* argv,
                                   const EnvironmentReader& getenv, std::ostream& out,
                                   std::ostream& err) {
  CLI::App app{"haptic-server: the haptic simulation service"};
  ServerFlags flags;
  std::string record_frames = "full";
  std::string record_scenes = "all";
  std::string cpus;
  AddServingFlags(app, flags);
  AddRecordingFlags(app, flags.server.recording, record_frames, record_scenes);
  AddLimitFlags(app, flags.server.limits);
  AddSteppingFlags(app, flags, cpus);
  AddAgonesFlags(app, flags.agones);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int parse_code = app.exit(e, out, err);
    return {.flags = std::nullopt, .exit_code = parse_code == 0 ? 0 : kServerExitUsage};
  }
  if (!ReadAgonesPort(getenv, flags.agones.sdk_port, err) || !ReadCpus(app, cpus, flags, err)) {
    return {.flags = std::nullopt, .exit_code = kServerExitUsage};
  }
  flags.server.recording.frames = record_frames == "digest" ? haptics::v1::FRAME_RECORDING_DIGEST
                                                            : haptics::v1::FRAME_RECORDING_FULL;
  flags.server.recording.all_scenes = record_scenes == "all";
  return {.flags = std::move(flags), .exit_code = 0};
}

}  // namespace hs
