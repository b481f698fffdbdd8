#include "tests/server/server_process.h"
#include "tests/common/test_data_dir.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace hs::testing {

ServerProcess::ServerProcess(const std::vector<std::string>& extra,
                             const std::vector<std::string>& environment,
                             const std::string& listen) {
  int fds[2];
  EXPECT_EQ(pipe(fds), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  const std::string scene = hs::ScenesDir() + "/probe_on_torus.textproto";
  std::vector<const char*> argv = {HS_HAPTIC_SERVER, "--listen", listen.c_str(), "--scene",
                                   scene.c_str()};
  for (const std::string& arg : extra) argv.push_back(arg.c_str());
  argv.push_back(nullptr);
  std::string temporary = (std::filesystem::temp_directory_path() / "hs-server-XXXXXX").string();
  EXPECT_NE(mkdtemp(temporary.data()), nullptr);
  temporary_dir_ = temporary;
  const std::string tmpdir = "TMPDIR=" + temporary_dir_;
  // First: getenv takes the first of two entries of one name.
  std::vector<const char*> envp = {tmpdir.c_str()};
  for (char** e = environ; *e != nullptr; ++e) envp.push_back(*e);
  for (const std::string& e : environment) envp.push_back(e.c_str());
  envp.push_back(nullptr);
  EXPECT_EQ(
      posix_spawn(&pid_, HS_HAPTIC_SERVER, &actions, nullptr, const_cast<char* const*>(argv.data()),
                  const_cast<char* const*>(envp.data())),
      0);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  stderr_ = fdopen(fds[0], "r");
  // "haptic-server: listening on port N"
  char line[512];
  while (port_ == 0 && fgets(line, sizeof line, stderr_) != nullptr) {
    startup_ += line;
    if (const char* at = strstr(line, "listening on port ")) port_ = atoi(at + 18);
  }
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0 && !waited_) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (stderr_ != nullptr) fclose(stderr_);
  std::error_code error;
  std::filesystem::remove_all(temporary_dir_, error);
}

std::string ServerProcess::LineWith(const char* text) {
  char line[512];
  while (fgets(line, sizeof line, stderr_) != nullptr) {
    if (strstr(line, text) != nullptr) return line;
  }
  return "";
}

void ServerProcess::Signal(int signal) { kill(pid_, signal); }

int ServerProcess::StopWith(int signal) {
  kill(pid_, signal);
  int status = 0;
  waitpid(pid_, &status, 0);
  waited_ = true;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace hs::testing
