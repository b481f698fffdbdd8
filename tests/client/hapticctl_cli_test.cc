#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>
#include <utility>

#include "client/exit_codes.h"
#include "tests/common/test_data_dir.h"

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
  const std::string data = hs::TestDataDir();
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
  for (const char* command :
       {"scenes", "scenes list", "scenes create", "scenes show", "scenes delete", "upload",
        "delete-model", "objects", "objects add", "objects update", "objects remove", "health",
        "watch", "drive", "loadtest", "relay"}) {
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
  EXPECT_EQ(RunHapticctl("relay --to 127.0.0.1:9 --stall-prob 2"), kExitUsage);
  EXPECT_EQ(RunHapticctl("relay --to 127.0.0.1:9 --stall-ms nan --duration-s 1"), kExitUsage);
  EXPECT_EQ(RunHapticctl("relay --to 10.1.2.3:80 --duration-s 1"), kExitUsage);
  const std::string nowhere = " --server 127.0.0.1:1";
  EXPECT_EQ(RunHapticctl("scenes list" + nowhere), kExitUnavailable);
  EXPECT_EQ(RunHapticctl("health" + nowhere), kExitUnavailable);
  EXPECT_EQ(RunHapticctl("watch s --frames 1" + nowhere), kExitUnavailable);
}

// What the built hapticctl prints on stderr for `args`, and its exit status.
std::pair<std::string, int> StderrOf(const std::string& args) {
  const std::string command = std::string(HS_HAPTICCTL) + " " + args + " 2>&1 >/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  std::string text;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) text += buffer;
  const int status = pclose(pipe);
  return {text, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

// A malformed value is a wrong command line (exit 2, before any server is
// asked), with a message naming the flag; options given before the
// subcommand are named in the order given.
TEST(HapticctlCliTest, MalformedValuesAreUsageErrors) {
  const struct {
    std::string args;
    std::string message;
  } cases[] = {
      {"objects add s o --box 1,2", "--box: '1,2': expected 3 comma-separated numbers"},
      {"objects add s o --box 1,1,1 --pose 0,0,0", "--pose: '0,0,0': expected 6"},
      {"objects update s o --move-vertex 3:1,2", "--move-vertex: '1,2': expected 3"},
      {"objects update s o --move-vertex x:1,2,3", "--move-vertex: 'x:1,2,3': expected ID:x,y,z"},
      {"objects update s o --material 1,2,3", "--material: '1,2,3': expected 4"},
      {"objects add s o --box 1,nan,1", "--box: 'nan' is not a finite number"},
      {"drive --scene s --tool t --motion press --needs forse", "--needs: unknown effect 'forse'"},
      {"contact a.obj b.obj --direction 1,0", "--direction: '1,0': expected 3"},
      {"drive --scene s --tool t --operator press --latency-ms 5000", "--latency-ms: Value 5000"},
      {"drive --scene s --tool t --operator press --loss 0.9", "--loss: Value 0.9"},
      {"drive --scene s --tool t --operator press --jitter-ms -1", "--jitter-ms: Value -1"},
      {"drive --scene s --tool t --motion press --frame-rate-hz nan",
       "--frame-rate-hz must be a finite number from 1 to 100000"},
      {"loadtest --frame-rate-hz 0", "--frame-rate-hz must be a finite number from 1 to 100000"},
      {"loadtest --frame-rate-hz inf", "--frame-rate-hz must be a finite number"},
      {"loadtest --server-metrics 127.0.0.1:9464", "--server-metrics must be http://HOST:PORT"},
      {"drive --scene s --tool t --operator press --stall-prob 1.5", "--stall-prob: Value 1.5"},
      {"drive --scene s --tool t --operator press --stall-ms -1", "--stall-ms: Value -1"},
      {"drive --scene s --tool t --operator press --stall-ms nan", "stall time must be a number"},
      {"drive --scene s --tool t --operator press --passivity-damping nan",
       "--passivity-damping must be a number from 0 to 1000"},
      {"drive --scene s --tool t --operator press --passivity-damping -1",
       "--passivity-damping: Value -1"},
      {"--server 1.2.3.4:5 scenes list",
       "options go after the subcommand (hapticctl SUBCOMMAND [OPTIONS]); not expected before "
       "it: --server"},
  };
  for (const auto& c : cases) {
    const auto [text, code] = StderrOf(c.args + " --server 127.0.0.1:1");
    EXPECT_EQ(code, kExitUsage) << c.args << "\n" << text;
    EXPECT_NE(text.find(c.message), std::string::npos) << c.args << "\n" << text;
  }
}

}  // namespace
}  // namespace hs::cli
