#pragma once
// `hapticctl objects add|update|remove SCENE ...`: changes the objects of
// a scene on a server (SceneService AddObject, UpdateObject, RemoveObject).

#include <ostream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct ObjectsArgs {
  ConnectionOptions server;
  /// "add", "update" or "remove".
  std::string action;
  std::string scene;
  /// The object's name (add: the new object's).
  std::string object;
  /// add: "fixed" or "tool".
  std::string kind = "fixed";
  /// add, one of: a box "x,y,z" (full sides, metres), a sphere radius
  /// (metres, 3 subdivisions), an uploaded model id, or a file holding a
  /// whole haptics.v1.SceneObject (text format, or JSON for *.json).
  std::string box;
  double sphere_radius_m = 0;
  std::string model_id;
  std::string object_file;
  /// add, update: the pose X_WO "x,y,z,rx,ry,rz" (metres, rotation vector
  /// in radians).
  std::string pose;
  /// update: a material "stiffness,damping,static,dynamic" (N/m, N s/m,
  /// two friction coefficients) for `face_group` (empty: every group).
  std::string material;
  std::string face_group;
  /// update: vertex moves "ID:x,y,z" (object frame, metres).
  std::vector<std::string> vertex_moves;
  /// The resulting haptics.v1.SceneInfo as one line of JSON.
  bool json = false;
};

/// Runs the action and prints the scene's new state to `out`. kExitOk;
/// kExitFailure for a bad value or file given here; else the exit status
/// of the gRPC status (server_call.h), reported on `err`.
int RunObjects(const ObjectsArgs& args, std::ostream& out, std::ostream& err);

/// Adds `objects` and its three subcommands to `app`; `exit_code`
/// receives the result.
void AddObjectsCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
