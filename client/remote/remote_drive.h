#pragma once
// `hapticctl drive --operator press|slide|tap`: a simulated hand
// (remote_run.h) holding the SDK's haptics::Device on a tool of a scene,
// whose streams cross a simulated link of --latency-ms, --jitter-ms,
// --loss and --stall-prob/--stall-ms (shaped_stream.h). When
// the link is not ideal, or a reference channel is given (the server
// itself when `channel` goes through a relay), a run over an ideal link
// comes first: the reference of force_rms_error_n.

#include <memory>
#include <ostream>
#include <string>

#include <grpcpp/grpcpp.h>

#include "client/remote/remote_run.h"

namespace hs::cli {

struct RemoteDriveArgs {
  std::string scene;
  std::string tool;
  RemoteRunOptions run{};
  double duration_s = 4;
  /// Write "t_s,fx,fy,fz,x,y,z" per tick (the rendered force, N, and the
  /// device position, m) to this file; empty for none.
  std::string trace_path;
  bool json = false;
  /// Frames a second asked of the server (frame_rate_args.h); 0: as many
  /// as poses go (run.pose_rate_hz, within the range), as the SDK's Device.
  double frame_rate_hz = 0;
};

/// Runs and prints the summary to `out`: one JSON object with --json.
/// kExitOk, or the exit status of a failed stream (reported on `err`).
/// `reference_channel`: where the reference run goes (null: `channel`).
int RunRemoteDrive(const RemoteDriveArgs& args, const std::shared_ptr<grpc::Channel>& channel,
                   const std::shared_ptr<grpc::Channel>& reference_channel, const Isometry3d& start,
                   std::ostream& out, std::ostream& err);

}  // namespace hs::cli
