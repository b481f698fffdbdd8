#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "client/exit_codes.h"

namespace hs::cli {
namespace {

// Runs the built hapticctl with `args`, output discarded, and returns its exit status.
int RunHapticctl(const std::string& args) {
  const std::string command = std::string(HS_HAPTICCTL) + " " + args + " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The documented exit statuses hold for the binary: 0 on success, 1 when
// the file cannot be read, 2 for a wrong command line, 0 for --help.
TEST(HapticctlCliTest, ExitStatuses) {
  const std::string data = HS_TEST_DATA_DIR;
  EXPECT_EQ(RunHapticctl("inspect " + data + "/cube.iv"), kExitOk);
  EXPECT_EQ(RunHapticctl("inspect --json " + data + "/cube_binary.stl"), kExitOk);
  EXPECT_EQ(RunHapticctl("inspect " + data + "/truncated_binary.stl"), kExitFailure);
  EXPECT_EQ(RunHapticctl("inspect /nonexistent.obj"), kExitFailure);
  EXPECT_EQ(RunHapticctl("inspect"), kExitUsage);
  EXPECT_EQ(RunHapticctl("inspect --unit-scale -1 " + data + "/cube.iv"), kExitUsage);
  EXPECT_EQ(RunHapticctl("no-such-command"), kExitUsage);
  EXPECT_EQ(RunHapticctl("--help"), kExitOk);
  EXPECT_EQ(RunHapticctl("inspect --help"), kExitOk);
}

// Every server command has --help (exit 0), rejects a wrong command line
// with 2, and exits 3 when no server listens.
TEST(HapticctlCliTest, ServerCommands) {
  for (const char* command : {"scenes", "scenes list", "scenes create", "scenes show",
                              "scenes delete", "upload", "objects", "objects add", "objects update",
                              "objects remove", "health", "watch", "drive", "loadtest"}) {
    EXPECT_EQ(RunHapticctl(std::string(command) + " --help"), kExitOk) << command;
  }
  EXPECT_EQ(RunHapticctl("scenes"), kExitUsage);
  EXPECT_EQ(RunHapticctl("scenes show"), kExitUsage);
  EXPECT_EQ(RunHapticctl("objects add s o --kind wobbly --box 1,1,1"), kExitUsage);
  EXPECT_EQ(RunHapticctl("drive --scene s --tool t"), kExitUsage);
  EXPECT_EQ(RunHapticctl("drive --scene s --tool t --path p.csv --motion press"), kExitUsage);
  EXPECT_EQ(RunHapticctl("watch s --parts colours"), kExitUsage);
  EXPECT_EQ(RunHapticctl("loadtest --clients 65"), kExitUsage);
  EXPECT_EQ(RunHapticctl("loadtest --duration 61"), kExitUsage);
  EXPECT_EQ(RunHapticctl("loadtest --server 10.1.2.3:50051"), kExitUsage);
  const std::string nowhere = " --server 127.0.0.1:1";
  EXPECT_EQ(RunHapticctl("scenes list" + nowhere), kExitUnavailable);
  EXPECT_EQ(RunHapticctl("health" + nowhere), kExitUnavailable);
  EXPECT_EQ(RunHapticctl("watch s --frames 1" + nowhere), kExitUnavailable);
}

}  // namespace
}  // namespace hs::cli
