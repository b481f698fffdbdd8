#pragma once
// `hapticctl relay --to HOST:PORT [--listen HOST:PORT] [--one-way-ms MS]
// [--jitter-ms MS] [--stall-prob P --stall-ms MS] [--seed N]
// [--allow-remote] [--duration-s S]`: a TCP relay (tcp_relay.h) between a
// client and a server on this machine, so that a real gRPC stream crosses
// a long link with jitter and head-of-line stalls. Prints the address it
// listens on, then relays until Ctrl-C or the duration ends, then its
// counters.

#include <ostream>

#include "CLI/CLI.hpp"
#include "client/relay/tcp_relay.h"

namespace hs::cli {

struct RelayArgs {
  RelayOptions relay{};
  /// Stop after this many seconds; 0: at Ctrl-C.
  double duration_s = 0;
};

/// Relays; kExitOk when it ran to its end, kExitUsage (reported on `err`)
/// for a value out of range or a refused address, kExitFailure when it
/// cannot listen.
int RunRelay(const RelayArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `relay` subcommand to `app`; `exit_code` receives its result.
void AddRelayCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
