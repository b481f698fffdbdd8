#include "server/server_flags.h"
#include "server/cpu_affinity.h"
#include "tests/common/test_data_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace hs {
namespace {

// A file that exists, for the flags that check.
const std::string kExisting = hs::TestDataDir() + "/cube.obj";

// A CPU number the process may not run on.
int CpuNotAllowed() {
  const std::vector<int> allowed = AllowedCpus();
  int cpu = 0;
  while (std::find(allowed.begin(), allowed.end(), cpu) != allowed.end()) ++cpu;
  return cpu;
}

// ParseServerFlags on `args` (after the program's name) and `environment`,
// with what it printed.
struct Outcome {
  ParsedServerFlags parsed;
  std::string out, err;
};
Outcome Parse(const std::vector<std::string>& args,
              const std::map<std::string, std::string>& environment = {}) {
  std::vector<const char*> argv = {"haptic-server"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  const EnvironmentReader getenv = [&](const char* name) -> const char* {
    const auto it = environment.find(name);
    return it == environment.end() ? nullptr : it->second.c_str();
  };
  std::ostringstream out, err;
  Outcome outcome;
  outcome.parsed = ParseServerFlags(static_cast<int>(argv.size()), argv.data(), getenv, out, err);
  outcome.out = out.str();
  outcome.err = err.str();
  return outcome;
}

// No flags and no environment give the options' own defaults, threads one
// per CPU the process may use up to 4, no --cpus, and no Agones.
TEST(ServerFlagsTest, NothingGivenIsTheDefaults) {
  const Outcome o = Parse({});
  ASSERT_TRUE(o.parsed.flags) << o.err;
  const ServerFlags& flags = *o.parsed.flags;
  const ServerOptions defaults;
  EXPECT_EQ(flags.server.listen, defaults.listen);
  EXPECT_EQ(flags.server.tokens_file, "");
  EXPECT_EQ(flags.server.state_dir, "");
  EXPECT_EQ(flags.server.recording.frames, defaults.recording.frames);
  EXPECT_EQ(flags.server.recording.all_scenes, defaults.recording.all_scenes);
  EXPECT_EQ(flags.server.recording.sync_ms, defaults.recording.sync_ms);
  EXPECT_EQ(flags.server.limits.max_scenes, defaults.limits.max_scenes);
  EXPECT_EQ(flags.server.limits.threads_per_scene,
            static_cast<int>(std::clamp<size_t>(AllowedCpus().size(), 1, 4)));
  EXPECT_TRUE(flags.cpus.empty());
  EXPECT_EQ(flags.agones.sdk_port, 0);
  EXPECT_EQ(flags.agones.idle_shutdown_s, AgonesOptions{}.idle_shutdown_s);
  EXPECT_TRUE(flags.scene_files.empty());
  EXPECT_EQ(flags.metrics_address, "");
  EXPECT_EQ(o.out + o.err, "");
}

// Each flag lands in its option, the word-valued recording flags as the
// values they name, repeated --scene files in order.
TEST(ServerFlagsTest, FlagsLandInTheirOptions) {
  const Outcome o = Parse({"--listen",
                           "127.0.0.1:0",
                           "--scene",
                           kExisting,
                           "--scene",
                           kExisting,
                           "--metrics",
                           "127.0.0.1:9464",
                           "--state-dir",
                           "/s",
                           "--record-dir",
                           "/r",
                           "--record-frames",
                           "digest",
                           "--record-scenes",
                           "requested",
                           "--record-sync-ms",
                           "20",
                           "--max-scenes",
                           "7",
                           "--threads-per-scene",
                           "3",
                           "--realtime-priority",
                           "10",
                           "--device-timeout-s",
                           "2.5",
                           "--agones-idle-shutdown-s",
                           "5",
                           "--insecure-listen"});
  ASSERT_TRUE(o.parsed.flags) << o.err;
  const ServerFlags& flags = *o.parsed.flags;
  EXPECT_EQ(flags.server.listen, "127.0.0.1:0");
  EXPECT_EQ(flags.scene_files, (std::vector<std::string>{kExisting, kExisting}));
  EXPECT_EQ(flags.metrics_address, "127.0.0.1:9464");
  EXPECT_EQ(flags.server.state_dir, "/s");
  EXPECT_EQ(flags.server.recording.dir, "/r");
  EXPECT_EQ(flags.server.recording.frames, haptics::v1::FRAME_RECORDING_DIGEST);
  EXPECT_FALSE(flags.server.recording.all_scenes);
  EXPECT_EQ(flags.server.recording.sync_ms, 20);
  EXPECT_EQ(flags.server.limits.max_scenes, 7);
  EXPECT_EQ(flags.server.limits.threads_per_scene, 3);
  EXPECT_EQ(flags.server.limits.realtime_priority, 10);
  EXPECT_EQ(flags.server.limits.device_timeout_s, 2.5);
  EXPECT_EQ(flags.agones.idle_shutdown_s, 5);
  EXPECT_TRUE(flags.server.insecure_listen);
}

// --cpus lands sorted; the threads of a scene default to one per CPU it
// names (up to 4), and --threads-per-scene still wins.
TEST(ServerFlagsTest, CpusSetTheThreadsDefault) {
  const std::vector<int> allowed = AllowedCpus();
  const std::string first = std::to_string(allowed.front());
  const Outcome one = Parse({"--cpus", first});
  ASSERT_TRUE(one.parsed.flags) << one.err;
  EXPECT_EQ(one.parsed.flags->cpus, std::vector<int>{allowed.front()});
  EXPECT_EQ(one.parsed.flags->server.limits.threads_per_scene, 1);

  // More threads than CPUs: as asked, with a warning.
  const Outcome given = Parse({"--threads-per-scene", "3", "--cpus", first});
  ASSERT_TRUE(given.parsed.flags) << given.err;
  EXPECT_EQ(given.parsed.flags->server.limits.threads_per_scene, 3);
  EXPECT_NE(given.err.find("warning: --threads-per-scene 3 on 1 CPU"), std::string::npos)
      << given.err;

  if (allowed.size() >= 3) {
    const Outcome two =
        Parse({"--cpus", std::to_string(allowed[0]) + "," + std::to_string(allowed[2])});
    ASSERT_TRUE(two.parsed.flags) << two.err;
    EXPECT_EQ(two.parsed.flags->server.limits.threads_per_scene, 2);
  }

  std::string every;
  for (const int cpu : allowed) every = std::to_string(cpu) + (every.empty() ? "" : ",") + every;
  const Outcome all = Parse({"--cpus", every});
  ASSERT_TRUE(all.parsed.flags) << all.err;
  EXPECT_EQ(all.parsed.flags->cpus, allowed);
  EXPECT_EQ(all.parsed.flags->server.limits.threads_per_scene,
            static_cast<int>(std::clamp<size_t>(allowed.size(), 1, 4)));
}

// A bad command line gives no flags, exit status 2 and a message on err
// that names the flag; nothing on out.
TEST(ServerFlagsTest, BadFlagsExitTwoNamingTheFlag) {
  const std::vector<std::vector<std::string>> bad = {
      {"--threads-per-scene", "0"},
      {"--cpus", ""},
      {"--cpus", "0-"},
      {"--cpus", std::to_string(CpuNotAllowed())},
      {"--threads-per-scene", "65"},
      {"--realtime-priority", "100"},
      {"--record-frames", "some"},
      {"--record-scenes", "none"},
      {"--record-sync-ms", "0"},
      {"--record-max-bytes", "1000"},
      {"--device-timeout-s", "3601"},
      {"--agones-health-interval-s", "0"},
      {"--max-scenes", "many"},
      {"--tls-cert", kExisting + ".missing"},
      {"--scene", kExisting + ".missing"},
      {"--no-such-flag"},
  };
  for (const std::vector<std::string>& args : bad) {
    const Outcome o = Parse(args);
    EXPECT_FALSE(o.parsed.flags) << args[0];
    EXPECT_EQ(o.parsed.exit_code, kServerExitUsage) << args[0];
    EXPECT_NE(o.err.find(args[0]), std::string::npos) << args[0] << ": " << o.err;
    EXPECT_EQ(o.out, "") << args[0];
  }
}

// --help prints the usage, every flag in it, on out and exits 0.
TEST(ServerFlagsTest, HelpExitsZero) {
  const Outcome o = Parse({"--help"});
  EXPECT_FALSE(o.parsed.flags);
  EXPECT_EQ(o.parsed.exit_code, 0);
  for (const char* flag : {"--listen", "--record-frames", "--threads-per-scene", "--cpus",
                           "--agones-idle-shutdown-s", "--max-vertex-moves"}) {
    EXPECT_NE(o.out.find(flag), std::string::npos) << flag;
  }
  EXPECT_EQ(o.err, "");
}

// AGONES_SDK_HTTP_PORT sets the SDK's port (1 to 65535); unset or empty
// means not on Agones.
TEST(ServerFlagsTest, AgonesPortComesFromTheEnvironment) {
  for (const int port : {1, 9358, 65535}) {
    const Outcome o = Parse({}, {{"AGONES_SDK_HTTP_PORT", std::to_string(port)}});
    ASSERT_TRUE(o.parsed.flags) << o.err;
    EXPECT_EQ(o.parsed.flags->agones.sdk_port, port);
  }
  const Outcome empty = Parse({}, {{"AGONES_SDK_HTTP_PORT", ""}});
  ASSERT_TRUE(empty.parsed.flags);
  EXPECT_EQ(empty.parsed.flags->agones.sdk_port, 0);
  const Outcome other = Parse({}, {{"OTHER", "1"}});
  ASSERT_TRUE(other.parsed.flags);
  EXPECT_EQ(other.parsed.flags->agones.sdk_port, 0);
}

// An AGONES_SDK_HTTP_PORT that is no port gives no flags, exit status 2
// and a message naming the variable and its value.
TEST(ServerFlagsTest, BadAgonesPortExitsTwo) {
  for (const std::string value : {"0", "65536", "-1", "port", "80x"}) {
    const Outcome o = Parse({}, {{"AGONES_SDK_HTTP_PORT", value}});
    EXPECT_FALSE(o.parsed.flags) << value;
    EXPECT_EQ(o.parsed.exit_code, kServerExitUsage) << value;
    EXPECT_NE(o.err.find("AGONES_SDK_HTTP_PORT='" + value + "'"), std::string::npos) << o.err;
  }
}

}  // namespace
}  // namespace hs
