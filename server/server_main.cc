// haptic-server: serves haptics.v1 SceneService and SessionService.
// Only wiring and flags: the server itself is HapticServer.

#include <signal.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <thread>

#include "CLI/CLI.hpp"
#include "absl/strings/numbers.h"
#include "common/api/scene_file.h"
#include "common/net/address.h"
#include "server/agones/agones_lifecycle.h"
#include "server/agones/server_activity.h"
#include "server/haptic_server.h"

int main(int argc, char** argv) {
  CLI::App app{"haptic-server: the haptic simulation service"};
  hs::ServerOptions options;
  std::vector<std::string> scene_files;
  std::string metrics_address;
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
  app.add_option("--scene", scene_files, "Scene file to load at start (repeatable)")
      ->check(CLI::ExistingFile);
  app.add_option("--metrics", metrics_address, "host:port to serve Prometheus /metrics on");
  app.add_option("--model-dir", options.model_dir,
                 "Folder for uploaded models (default: STATE_DIR/models, else a temporary folder)");
  app.add_option("--state-dir", options.state_dir,
                 "Keep scenes created or changed over the API (scenes.db, SQLite) and uploaded "
                 "models (models/) in this folder across restarts; without it they live in "
                 "memory");
  app.add_option("--record-dir", options.recording.dir,
                 "Record each scene's session (spec, edits, device poses, streams, frames) into "
                 "this folder, one file per session (docs/recording.md)");
  std::string record_frames = "full";
  app.add_option("--record-frames", record_frames,
                 "What recordings keep of each frame: 'full', or 'digest' (its SHA-256)")
      ->check(CLI::IsMember({"full", "digest"}))
      ->capture_default_str();
  std::string record_scenes = "all";
  app.add_option("--record-scenes", record_scenes,
                 "Which scenes --record-dir records: 'all', or 'requested' (those whose spec "
                 "sets record)")
      ->check(CLI::IsMember({"all", "requested"}))
      ->capture_default_str();
  app.add_option("--record-sync-ms", options.recording.sync_ms,
                 "Longest a recorded record waits before it is synced to the disk, ms")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  app.add_option("--record-max-bytes", options.recording.max_file_bytes,
                 "A recording file past this size rolls over to the session's next part")
      ->check(CLI::Range(int64_t{1} << 16, int64_t{1} << 40))
      ->capture_default_str();
  app.add_option("--max-scenes", options.limits.max_scenes)->capture_default_str();
  app.add_option("--max-clients", options.limits.max_clients)->capture_default_str();
  app.add_option("--max-objects", options.limits.max_objects_per_scene)->capture_default_str();
  app.add_option("--max-triangles", options.limits.max_triangles_per_scene)->capture_default_str();
  app.add_option("--max-spec-bytes", options.limits.max_spec_bytes,
                 "Largest scene spec, serialized, bytes (it comes back in every SceneInfo)")
      ->capture_default_str();
  app.add_option("--max-streams-per-caller", options.limits.per_caller.streams,
                 "Open Interact and Watch streams per caller (token, or peer on an open server)")
      ->capture_default_str();
  app.add_option("--max-uploads-per-caller", options.limits.per_caller.uploads_in_flight,
                 "Uploads in progress per caller")
      ->capture_default_str();
  app.add_option("--max-models-per-caller", options.limits.per_caller.models,
                 "Stored models per caller (until deleted)")
      ->capture_default_str();
  app.add_option("--max-scenes-per-caller", options.limits.per_caller.scenes,
                 "Scenes per caller (until deleted)")
      ->capture_default_str();
  app.add_option("--max-vertex-moves", options.limits.max_vertex_moves_per_request,
                 "Vertex moves in one UpdateObject")
      ->capture_default_str();
  // One per core, up to 4: a step rarely has more tools than that busy.
  options.limits.threads_per_scene =
      static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 4u));
  app.add_option("--threads-per-scene", options.limits.threads_per_scene,
                 "Threads that step one scene's tools at once")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--realtime-priority", options.limits.realtime_priority,
                 "SCHED_FIFO priority (1-99) of the threads that step scenes, so that a busy "
                 "machine delays no step; needs root or CAP_SYS_NICE, checked at start. 0: the "
                 "default scheduler. A scene whose step outlasts its period then holds its cores")
      ->check(CLI::Range(0, 99))
      ->capture_default_str();
  app.add_option("--device-timeout-s", options.limits.device_timeout_s,
                 "A device that sends no pose for this long is ended (DEADLINE_EXCEEDED) and "
                 "its tool released where it was; 0: never")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  hs::AgonesOptions agones_options;
  app.add_option("--agones-health-interval-s", agones_options.health_interval_s,
                 "On Agones (AGONES_SDK_HTTP_PORT set): seconds between health pings")
      ->check(CLI::Range(0.1, 300.0))
      ->capture_default_str();
  app.add_option("--agones-idle-shutdown-s", agones_options.idle_shutdown_s,
                 "On Agones: ask to be shut down once the last client has left and this many "
                 "seconds passed")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (const char* port = std::getenv("AGONES_SDK_HTTP_PORT"); port != nullptr && *port != 0) {
    if (!absl::SimpleAtoi(port, &agones_options.sdk_port) || agones_options.sdk_port < 1 ||
        agones_options.sdk_port > 65535) {
      std::cerr << "haptic-server: AGONES_SDK_HTTP_PORT='" << port << "' is not a port\n";
      return 1;
    }
  }
  options.recording.frames = record_frames == "digest" ? haptics::v1::FRAME_RECORDING_DIGEST
                                                       : haptics::v1::FRAME_RECORDING_FULL;
  options.recording.all_scenes = record_scenes == "all";

  // SIGTERM, SIGINT and SIGHUP are taken by sigwait below, not by any thread.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  hs::Metrics metrics;
  if (!metrics_address.empty()) {
    if (absl::Status s = metrics.Expose(metrics_address); !s.ok()) {
      std::cerr << "haptic-server: " << s.message() << "\n";
      return 1;
    }
  }
  absl::StatusOr<std::unique_ptr<hs::HapticServer>> server =
      hs::HapticServer::Start(options, metrics);
  if (!server.ok()) {
    std::cerr << "haptic-server: " << server.status().message() << "\n";
    return 1;
  }
  std::string first_scene;  // the game server's scene on Agones
  for (const std::string& file : scene_files) {
    absl::StatusOr<haptics::v1::SceneSpec> spec = hs::ReadSceneFile(file);
    if (spec.ok() && first_scene.empty()) first_scene = spec->name();
    if (spec.ok() && (*server)->registry().Find(spec->name()).ok()) {
      std::cerr << "haptic-server: scene '" << spec->name() << "' restored from "
                << options.state_dir << ", as last changed over the API; " << file
                << " not loaded\n";
      continue;
    }
    absl::StatusOr<hs::RunnerInfo> info =
        spec.ok() ? (*server)->registry().Create(*spec,
                                                 std::filesystem::path(file).parent_path().string(),
                                                 hs::SceneRegistry::Deadline::max(), /*keep=*/false)
                  : absl::StatusOr<hs::RunnerInfo>(spec.status());
    if (!info.ok()) {
      std::cerr << "haptic-server: " << file << ": " << info.status().message() << "\n";
      return 1;
    }
    std::cerr << "haptic-server: scene '" << info->spec.name() << "' from " << file << "\n";
  }
  if (!options.tls.enabled() && !hs::IsLoopbackAddress(options.listen)) {
    std::cerr << "haptic-server: WARNING: " << options.listen
              << " is served without TLS: anyone on the network can read and send its traffic\n";
  }
  if (options.tokens_file.empty()) {
    std::cerr << "haptic-server: no --tokens: open to every client that reaches it\n";
  }
  if (options.state_dir.empty()) {
    std::cerr << "haptic-server: no --state-dir: scenes created over the API and uploaded "
                 "models are lost when it stops\n";
  } else {
    std::cerr << "haptic-server: state kept in " << options.state_dir << " ("
              << (*server)->registry().List().size() << " scenes running)\n";
  }
  if (!options.recording.dir.empty()) {
    std::cerr << "haptic-server: recording "
              << (options.recording.all_scenes ? "every scene's session"
                                               : "the sessions of scenes that ask")
              << " into " << options.recording.dir << " (frames: " << record_frames << ")\n";
  }
  std::cerr << "haptic-server: listening on port " << (*server)->port() << std::endl;
  std::unique_ptr<hs::AgonesLifecycle> agones;
  if (agones_options.sdk_port != 0) {
    agones = std::make_unique<hs::AgonesLifecycle>(
        agones_options,
        [&server, first_scene] { return hs::ActivityOf((*server)->registry(), first_scene); },
        metrics, std::cerr);
  }

  int signal = 0;
  while (sigwait(&signals, &signal) == 0 && signal == SIGHUP) {
    const absl::StatusOr<size_t> tokens = (*server)->access().Reload();
    if (tokens.ok()) {
      std::cerr << "haptic-server: SIGHUP: " << *tokens << " tokens" << std::endl;
    } else {
      std::cerr << "haptic-server: SIGHUP: " << tokens.status().message()
                << "; the tokens read before stay" << std::endl;
    }
  }
  std::cerr << "haptic-server: " << (signal == SIGTERM ? "SIGTERM" : "SIGINT")
            << ", shutting down\n";
  (*server)->Shutdown();
  agones.reset();
  return 0;
}
