// haptic-server: serves haptics.v1 SceneService and SessionService.
// Only wiring: the flags are server_flags.h, the server itself HapticServer.

#include <signal.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "common/api/scene_file.h"
#include "common/net/address.h"
#include "server/agones/agones_lifecycle.h"
#include "server/agones/server_activity.h"
#include "server/cpu_affinity.h"
#include "server/haptic_server.h"
#include "server/server_flags.h"

namespace {

// Blocks SIGTERM, SIGINT and SIGHUP in this thread and every thread started
// after it, so that only WaitForStop's sigwait takes them.
sigset_t BlockStopSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  return signals;
}

// Starts the --scene files' scenes, in order; a scene the state folder
// restored, as last changed over the API, is left as it is. Returns the
// first file's scene name (the game server's scene on Agones), or the first
// file that could not be read or started.
absl::StatusOr<std::string> StartSceneFiles(const hs::ServerFlags& flags,
                                            hs::SceneRegistry& registry) {
  std::string first_scene;
  for (const std::string& file : flags.scene_files) {
    absl::StatusOr<haptics::v1::SceneSpec> spec = hs::ReadSceneFile(file);
    if (spec.ok() && first_scene.empty()) first_scene = spec->name();
    if (spec.ok() && registry.Find(spec->name()).ok()) {
      std::cerr << "haptic-server: scene '" << spec->name() << "' restored from "
                << flags.server.state_dir << ", as last changed over the API; " << file
                << " not loaded\n";
      continue;
    }
    absl::StatusOr<hs::RunnerInfo> info =
        spec.ok() ? registry.Create(*spec, std::filesystem::path(file).parent_path().string(),
                                    hs::SceneRegistry::Deadline::max(), /*keep=*/false)
                  : absl::StatusOr<hs::RunnerInfo>(spec.status());
    if (!info.ok()) {
      return absl::Status(info.status().code(), file + ": " + std::string(info.status().message()));
    }
    std::cerr << "haptic-server: scene '" << info->spec.name() << "' from " << file << "\n";
  }
  return first_scene;
}

// What the operator should know of how the server runs: who can reach it,
// what it keeps, what it records.
void PrintSetup(const hs::ServerOptions& options, hs::HapticServer& server) {
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
              << server.registry().List().size() << " scenes running)\n";
  }
  if (!options.recording.dir.empty()) {
    const bool digest = options.recording.frames == haptics::v1::FRAME_RECORDING_DIGEST;
    std::cerr << "haptic-server: recording "
              << (options.recording.all_scenes ? "every scene's session"
                                               : "the sessions of scenes that ask")
              << " into " << options.recording.dir << " (frames: " << (digest ? "digest" : "full")
              << ")\n";
  }
  std::cerr << "haptic-server: listening on port " << server.port() << std::endl;
}

// Serves until SIGTERM or SIGINT, which it returns; each SIGHUP re-reads
// the tokens file on the way.
int WaitForStop(const sigset_t& signals, hs::HapticServer& server) {
  int signal = 0;
  while (sigwait(&signals, &signal) == 0 && signal == SIGHUP) {
    const absl::StatusOr<size_t> tokens = server.access().Reload();
    if (tokens.ok()) {
      std::cerr << "haptic-server: SIGHUP: " << *tokens << " tokens" << std::endl;
    } else {
      std::cerr << "haptic-server: SIGHUP: " << tokens.status().message()
                << "; the tokens read before stay" << std::endl;
    }
  }
  return signal;
}

}  // namespace

int main(int argc, char** argv) {
  const hs::ParsedServerFlags parsed = hs::ParseServerFlags(
      argc, argv, [](const char* name) -> const char* { return std::getenv(name); }, std::cout,
      std::cerr);
  if (!parsed.flags) return parsed.exit_code;
  const hs::ServerFlags& flags = *parsed.flags;
  // Before any thread starts, so that every one inherits it.
  if (!flags.cpus.empty()) {
    if (absl::Status s = hs::RunOnCpus(flags.cpus); !s.ok()) {
      std::cerr << "haptic-server: --cpus: " << s.message() << "\n";
      return 1;
    }
  }
  const sigset_t signals = BlockStopSignals();

  hs::Metrics metrics;
  if (!flags.metrics_address.empty()) {
    if (absl::Status s = metrics.Expose(flags.metrics_address); !s.ok()) {
      std::cerr << "haptic-server: " << s.message() << "\n";
      return 1;
    }
  }
  absl::StatusOr<std::unique_ptr<hs::HapticServer>> server =
      hs::HapticServer::Start(flags.server, metrics);
  if (!server.ok()) {
    std::cerr << "haptic-server: " << server.status().message() << "\n";
    return 1;
  }
  const absl::StatusOr<std::string> first_scene = StartSceneFiles(flags, (*server)->registry());
  if (!first_scene.ok()) {
    std::cerr << "haptic-server: " << first_scene.status().message() << "\n";
    return 1;
  }
  PrintSetup(flags.server, **server);
  std::unique_ptr<hs::AgonesLifecycle> agones;
  if (flags.agones.sdk_port != 0) {
    agones = std::make_unique<hs::AgonesLifecycle>(
        flags.agones,
        [&server, scene = *first_scene] { return hs::ActivityOf((*server)->registry(), scene); },
        metrics, std::cerr);
  }

  const int signal = WaitForStop(signals, **server);
  std::cerr << "haptic-server: " << (signal == SIGTERM ? "SIGTERM" : "SIGINT")
            << ", shutting down\n";
  (*server)->Shutdown();
  agones.reset();
  return 0;
}
