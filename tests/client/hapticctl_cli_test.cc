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

}  // namespace
}  // namespace hs::cli
