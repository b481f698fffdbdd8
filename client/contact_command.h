#pragma once
// `hapticctl contact MOVING FIXED`: the contact set of two model files,
// computed locally.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct ContactArgs {
  std::string moving_file;
  std::string fixed_file;
  /// "x,y,z,rx,ry,rz": metres, then a rotation vector in radians.
  std::string pose_moving = "0,0,0,0,0,0";
  std::string pose_fixed = "0,0,0,0,0,0";
  /// "dx,dy,dz": direction of the moving object's motion, world frame.
  std::string direction;
  /// "paper" or "3d".
  std::string method = "3d";
  /// Bounding volume name (obbrss, obb, rss, kios, aabb).
  std::string bv = "obbrss";
  double relative_tolerance = 1e-9;
  /// Treat the direction as the whole last step and look along it.
  bool continuous = false;
  double unit_scale = 1.0;
  bool json = false;
};

/// Loads both files, poses them, and prints their ContactSet to `out`.
/// Returns kExitOk, or kExitFailure with the error on `err`.
int RunContact(const ContactArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `contact` subcommand to `app`; `exit_code` receives its result.
void AddContactCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
