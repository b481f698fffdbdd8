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
#include <optional>
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

}  // namespace

int RunView(const ViewArgs& args, std::ostream& out, std::ostream& err) {
  const std::optional<HostPort> http = SplitHostPort(args.http);
  if (!http) {
    err << "view: --http must be HOST:PORT, not '" << args.http << "'\n";
    return kExitUsage;
  }
  ViewServerOptions web{.host = http->host, .port = http->port};
  web.tls_cert_file = args.http_tls_cert;
  web.tls_key_file = args.http_tls_key;
  const bool tls = !web.tls_cert_file.empty() || !web.tls_key_file.empty();
  if (tls && (web.tls_cert_file.empty() || web.tls_key_file.empty())) {
    err << "view: TLS needs both --http-tls-cert and --http-tls-key\n";
    return kExitUsage;
  }
  // Other machines would read the frames, and the token that lets a
  // page drive a tool, off the wire.
  if (!tls && !IsLoopbackAddress(args.http)) {
    if (!args.insecure_http) {
      err << "view: " << args.http
          << " is reachable from other machines: serve the page with TLS (--http-tls-cert, "
             "--http-tls-key), or give --insecure-http to serve it in the clear\n";
      return kExitUsage;
    }
    err << "view: warning: serving " << args.http
        << " in the clear (--insecure-http): anyone on the network path reads the scene and the "
           "page's token\n";
  }
  absl::StatusOr<Bridge> bridge = StartBridge(args.server, args.scene, web);
  if (!bridge.ok() && bridge.status().code() == absl::StatusCode::kInvalidArgument) {
    // A bad address or TLS file: the command line's fault.
    err << "view: " << bridge.status().message() << "\n";
    return kExitUsage;
  }
  if (!bridge.ok()) return ReportError("view", bridge.status(), err);
  out << "viewer on " << bridge->server->url() << std::endl;
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

void AddViewCommands(CLI::App& app, int& exit_code) {
  auto view = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Serve the browser viewer of a scene (docs/viewer.md) until Ctrl-C");
  AddConnectionOptions(*cmd, view->server);
  cmd->add_option("--scene", view->scene, "Scene name")->required();
  cmd->add_option("--http", view->http,
                  "HOST:PORT to serve the page on (loopback unless told otherwise; port 0: any)");
  cmd->add_option("--http-tls-cert", view->http_tls_cert,
                  "PEM certificate (chain) to serve the page over https and wss");
  cmd->add_option("--http-tls-key", view->http_tls_key, "PEM private key of --http-tls-cert");
  cmd->add_flag("--insecure-http", view->insecure_http,
                "Serve a non-loopback --http address without TLS (the traffic is readable)");
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
