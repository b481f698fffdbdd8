#pragma once
// The built haptic-server as a child process of a test: started on a free
// 127.0.0.1 port with the demo scene, its stderr read line by line, killed
// when the fixture goes. Its temporary folder (TMPDIR) is one of its own,
// removed once it has ended: a server killed with SIGKILL cannot remove
// what it made there (the folder for uploaded models without --state-dir).

#include <sys/types.h>

#include <cstdio>
#include <string>
#include <vector>

namespace hs::testing {

class ServerProcess {
 public:
  /// Starts the binary on `listen` with `extra` arguments after the demo
  /// scene, and `environment` ("NAME=value") added to this process's;
  /// returns once it listens (or ended: port() is then 0). A test that
  /// restarts a server gives the port of the one before.
  explicit ServerProcess(const std::vector<std::string>& extra = {},
                         const std::vector<std::string>& environment = {},
                         const std::string& listen = "127.0.0.1:0");
  /// SIGKILL unless it was ended with StopWith; removes its TMPDIR.
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  /// What it wrote to stderr until it listened (or ended).
  const std::string& startup() const { return startup_; }
  /// The next line of its stderr that holds `text`; empty at its end.
  std::string LineWith(const char* text);
  void Signal(int signal);
  /// Sends `signal` and returns the exit status (-1 unless it exited).
  int StopWith(int signal);

 private:
  pid_t pid_ = -1;
  FILE* stderr_ = nullptr;
  int port_ = 0;
  bool waited_ = false;
  std::string startup_;
  std::string temporary_dir_;
};

}  // namespace hs::testing
