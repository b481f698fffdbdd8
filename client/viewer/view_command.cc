#include "client/viewer/view_command.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "absl/cleanup/cleanup.h"
#include "client/channel.h"
#include "client/exit_codes.h"
#include "client/server_call.h"
#include "client/viewer/scene_link.h"
#include "client/viewer/view_server.h"
#include "common/net/address.h"

extern char** environ;

namespace hs::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct ViewArgs {
  ConnectionOptions server;
  std::string scene;
  std::string http = "127.0.0.1:8080";
  double duration_s = 0;
};

struct SnapshotArgs {
  ConnectionOptions server;
  std::string scene;
  std::string out;
  int width = 1280;
  int height = 800;
  std::string browser = "/usr/bin/chromium";
  double timeout_s = 30;
};

std::atomic<bool> g_interrupted{false};

void OnSignal(int) { g_interrupted = true; }

// Connects to the server and starts the web side on `web`.
struct Bridge {
  std::unique_ptr<SceneLink> link;
  std::unique_ptr<ViewServer> server;
};
absl::StatusOr<Bridge> StartBridge(const ConnectionOptions& connection, const std::string& scene,
                                   const ViewServerOptions& web) {
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(connection);
  if (!channel.ok()) return channel.status();
  Bridge bridge;
  bridge.link = std::make_unique<SceneLink>(*channel, scene);
  absl::StatusOr<std::unique_ptr<ViewServer>> server = ViewServer::Start(*bridge.link, web);
  if (!server.ok()) return server.status();
  bridge.server = std::move(*server);
  return bridge;
}

int RunView(const ViewArgs& args, std::ostream& out, std::ostream& err) {
  const std::optional<HostPort> http = SplitHostPort(args.http);
  if (!http) {
    err << "view: --http must be HOST:PORT, not '" << args.http << "'\n";
    return kExitUsage;
  }
  const ViewServerOptions web{.host = http->host, .port = http->port};
  absl::StatusOr<Bridge> bridge = StartBridge(args.server, args.scene, web);
  if (!bridge.ok()) return ReportError("view", bridge.status(), err);
  const std::string host =
      web.host.find(':') == std::string::npos ? web.host : "[" + web.host + "]";
  out << "viewer on http://" << host << ":" << bridge->server->port() << "/" << std::endl;
  signal(SIGINT, OnSignal);
  signal(SIGTERM, OnSignal);
  const Clock::time_point start = Clock::now();
  while (!g_interrupted &&
         (args.duration_s <= 0 ||
          Clock::now() - start < std::chrono::duration<double>(args.duration_s))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const ViewServer::Counters c = bridge->server->counters();
  err << "view: " << c.poses_forwarded << " poses forwarded, " << c.rejected_messages
      << " page messages rejected\n";
  return kExitOk;
}

// Runs `argv` with its output to `log` and waits up to `timeout_s`; -1 when
// it could not start or ran out of time (then killed).
int RunBrowser(const std::vector<std::string>& argv, const std::string& log, double timeout_s) {
  std::vector<char*> raw;
  for (const std::string& a : argv) raw.push_back(const_cast<char*>(a.c_str()));
  raw.push_back(nullptr);
  // Its chatter (no D-Bus, software GL) is not ours to print, unless it fails.
  posix_spawn_file_actions_t quiet;
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT, 0600);
  posix_spawn_file_actions_adddup2(&quiet, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, raw[0], &quiet, nullptr, raw.data(), environ);
  posix_spawn_file_actions_destroy(&quiet);
  if (spawned != 0) return -1;
  const Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                        std::chrono::duration<double>(timeout_s));
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The last `lines` lines of `path`, indented.
std::string Tail(const std::string& path, size_t lines) {
  std::ifstream in(path);
  std::vector<std::string> kept;
  for (std::string line; std::getline(in, line);) {
    kept.push_back(line);
    if (kept.size() > lines) kept.erase(kept.begin());
  }
  std::string out;
  for (const std::string& line : kept) out += "  " + line + "\n";
  return out;
}

bool IsPng(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  char magic[8] = {};
  file.read(magic, 8);
  return file && std::string(magic, 8) == "\x89PNG\r\n\x1a\n";
}

int RunSnapshot(const SnapshotArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<Bridge> bridge = StartBridge(args.server, args.scene, ViewServerOptions{});
  if (!bridge.ok()) return ReportError("snapshot", bridge.status(), err);
  // The page renders what the bridge holds: wait for the geometry and a frame.
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(10);
  SceneLink::State state = bridge->link->state();
  while (!(state.connected && state.geometry_json && bridge->link->latest().frame)) {
    if (Clock::now() > deadline) {
      err << "snapshot: " << (state.message.empty() ? "no frame from the scene" : state.message)
          << "\n";
      return kExitUnavailable;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    state = bridge->link->state();
  }
  const std::string url =
      "http://127.0.0.1:" + std::to_string(bridge->server->port()) + "/?snapshot=1";
  // A profile of its own: with the user's, a Chromium already running
  // would take the request and this one would end at once, drawing nothing.
  std::string scratch =
      (std::filesystem::temp_directory_path() / "hapticctl-snapshot-XXXXXX").string();
  if (!mkdtemp(scratch.data()))
    return ReportError("snapshot", "cannot make a temporary folder", err);
  const absl::Cleanup remove_scratch = [&] {
    std::error_code ignored;
    std::filesystem::remove_all(scratch, ignored);
  };
  const std::string log = scratch + "/chromium.log";
  // --no-sandbox: Chromium's sandbox cannot start as root (CI); the page
  // is our own, from loopback. --enable-unsafe-swiftshader: WebGL on the
  // CPU, where there is no GPU. The virtual time budget lets the page's
  // two fetches and its first render finish before the screenshot.
  const std::vector<std::string> argv = {
      args.browser,
      "--headless=new",
      "--user-data-dir=" + scratch + "/profile",
      "--no-sandbox",
      "--enable-unsafe-swiftshader",
      "--hide-scrollbars",
      "--virtual-time-budget=5000",
      "--window-size=" + std::to_string(args.width) + "," + std::to_string(args.height),
      "--screenshot=" + args.out,
      url};
  std::remove(args.out.c_str());
  // Chromium writes the file but makes no folder for it.
  const std::filesystem::path folder = std::filesystem::path(args.out).parent_path();
  std::error_code made;
  if (!folder.empty()) std::filesystem::create_directories(folder, made);
  if (made) return ReportError("snapshot", folder.string() + ": " + made.message(), err);
  const int status = RunBrowser(argv, log, args.timeout_s);
  if (status != 0 || !IsPng(args.out)) {
    err << "snapshot: " << args.browser
        << (status < 0 ? " did not start or did not finish in time"
                       : " ended with status " + std::to_string(status))
        << "; no PNG written. Its last lines:\n"
        << Tail(log, 10);
    std::remove(args.out.c_str());
    return kExitFailure;
  }
  out << "wrote " << args.out << "\n";
  return kExitOk;
}

}  // namespace

void AddViewCommands(CLI::App& app, int& exit_code) {
  auto view = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Serve the browser viewer of a scene (docs/viewer.md) until Ctrl-C");
  AddConnectionOptions(*cmd, view->server);
  cmd->add_option("--scene", view->scene, "Scene name")->required();
  cmd->add_option("--http", view->http,
                  "HOST:PORT to serve the page on (loopback unless told otherwise; port 0: any)");
  cmd->add_option("--duration", view->duration_s, "Stop after this many seconds (0: never)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->callback([view, &exit_code] { exit_code = RunView(*view, std::cout, std::cerr); });

  auto snap = std::make_shared<SnapshotArgs>();
  CLI::App* shot = app.add_subcommand(
      "snapshot", "Render a scene's current state to a PNG through the viewer's page (Chromium)");
  AddConnectionOptions(*shot, snap->server);
  shot->add_option("--scene", snap->scene, "Scene name")->required();
  shot->add_option("--out", snap->out, "PNG file to write")->required();
  shot->add_option("--width", snap->width, "Pixels")->check(CLI::Range(64, 8192));
  shot->add_option("--height", snap->height, "Pixels")->check(CLI::Range(64, 8192));
  shot->add_option("--browser", snap->browser, "Chromium to render with");
  shot->add_option("--render-timeout", snap->timeout_s, "Seconds the browser may take")
      ->check(CLI::Range(1.0, 600.0));
  shot->callback([snap, &exit_code] { exit_code = RunSnapshot(*snap, std::cout, std::cerr); });
}

}  // namespace hs::cli
