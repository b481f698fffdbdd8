#include "client/relay/relay_command.h"

#include <signal.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <thread>

#include "client/exit_codes.h"
#include "client/remote/link_schedule.h"
#include "client/server_call.h"

namespace hs::cli {
namespace {

using Clock = std::chrono::steady_clock;

std::atomic<bool> g_interrupted{false};

void OnSignal(int) { g_interrupted = true; }

}  // namespace

int RunRelay(const RelayArgs& args, std::ostream& out, std::ostream& err) {
  if (!(args.duration_s >= 0)) {
    err << "hapticctl relay: --duration-s must be >= 0\n";
    return kExitUsage;
  }
  absl::StatusOr<std::unique_ptr<TcpRelay>> relay = TcpRelay::Start(args.relay);
  if (!relay.ok()) {
    ReportError("relay", relay.status(), err);
    return relay.status().code() == absl::StatusCode::kInvalidArgument ? kExitUsage : kExitFailure;
  }
  out << "relay: listening on port " << (*relay)->port() << ", to " << args.relay.to << std::endl;
  signal(SIGINT, OnSignal);
  signal(SIGTERM, OnSignal);
  const Clock::time_point start = Clock::now();
  while (!g_interrupted &&
         (args.duration_s == 0 ||
          Clock::now() - start < std::chrono::duration<double>(args.duration_s))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  (*relay)->Stop();
  const TcpRelay::Counters c = (*relay)->counters();
  out << "relay: " << c.connections << " connections, " << c.bytes_up << " bytes up, "
      << c.bytes_down << " bytes down, " << c.stalls << " chunks stalled, at most "
      << c.peak_in_flight_bytes << " bytes held one way" << std::endl;
  return kExitOk;
}

void AddRelayCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RelayArgs>();
  RelayOptions& o = args->relay;
  CLI::App* cmd = app.add_subcommand(
      "relay",
      "Relay TCP connections through a simulated long link: latency, jitter, head-of-line "
      "stalls (docs/remote-haptics.md)");
  cmd->add_option("--to", o.to, "HOST:PORT to connect each client to")->required();
  cmd->add_option("--listen", o.listen, "HOST:PORT to accept on (port 0: any free one)")
      ->capture_default_str();
  cmd->add_option("--one-way-ms", o.one_way_ms, "Each chunk is held this long each way")
      ->check(CLI::Range(0.0, kMaxLinkMs / 2));
  cmd->add_option("--jitter-ms", o.jitter_ms, "Up to this much more each way, uniformly")
      ->check(CLI::Range(0.0, kMaxLinkMs));
  cmd->add_option("--stall-prob", o.stall_prob,
                  "Probability a chunk is held --stall-ms longer, with everything behind it")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--stall-ms", o.stall_ms, "How long a stalled chunk is held")
      ->check(CLI::Range(0.0, kMaxLinkMs));
  cmd->add_option("--seed", o.seed, "The link's random seed")->capture_default_str();
  cmd->add_flag("--allow-remote", o.allow_remote,
                "Allow addresses that are not on loopback (to listen on or connect to)");
  cmd->add_option("--duration-s", args->duration_s, "Stop after this many seconds (0: at Ctrl-C)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->callback([args, &exit_code] { exit_code = RunRelay(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
