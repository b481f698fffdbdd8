#include "common/sandbox/sandboxed_import.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "absl/cleanup/cleanup.h"
#include "absl/strings/str_cat.h"
#include "common/sandbox/import_codec.h"

extern char** environ;

namespace hs {
namespace {

namespace pb = haptics::internal;

// The worker's answer is a whole mesh; more than this is not one.
constexpr size_t kMaxOutcomeBytes = size_t{1} << 30;

absl::Status ForFile(const std::string& path, absl::string_view what) {
  return absl::InvalidArgumentError(absl::StrCat(path, ": ", what));
}

// What the child's stdout said before it closed, or the deadline passed.
struct Output {
  std::string bytes;
  bool timed_out = false;
};

Output ReadUntilClosed(int fd, std::chrono::steady_clock::time_point deadline) {
  Output out;
  char buffer[1 << 16];
  while (out.bytes.size() <= kMaxOutcomeBytes) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      out.timed_out = true;
      break;
    }
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;  // the deadline check above ends it
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    out.bytes.append(buffer, static_cast<size_t>(n));
  }
  return out;
}

// Sends on a socket without SIGPIPE when the worker is gone.
bool SendAll(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// Why a worker that ended with wait status `status` gave no outcome.
std::string Failure(int status, const SandboxLimits& limits) {
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGXCPU) return absl::StrCat("took more than ", limits.cpu_s, " s of CPU");
    const char* name = sigabbrev_np(signal);
    return absl::StrCat("the importer crashed (SIG", name == nullptr ? "?" : name,
                        "): the file is malformed or too deeply nested");
  }
  return absl::StrCat("the importer failed (exit status ", WEXITSTATUS(status), ")");
}

}  // namespace

std::string ImportWorkerPath() {
  if (const char* from_env = std::getenv("HAPTIC_IMPORT_WORKER")) return from_env;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path beside = self.parent_path() / "haptic-import";
    if (std::filesystem::exists(beside, error)) return beside.string();
  }
  return HS_IMPORT_WORKER_BUILD_PATH;
}

absl::StatusOr<ImportedModel> SandboxedImport(const std::string& path,
                                              const ImportOptions& options,
                                              const SandboxLimits& limits) {
  pb::ImportJob job;
  job.set_path(std::filesystem::absolute(path).string());
  OptionsToJob(options, job);
  job.set_cpu_s(limits.cpu_s);
  job.set_memory_bytes(limits.memory_bytes);
  job.set_stack_bytes(limits.stack_bytes);

  // The job goes over a socket (send can refuse SIGPIPE), the outcome over a pipe.
  int to_child[2], from_child[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, to_child) != 0) {
    return absl::UnavailableError("cannot make a socket pair");
  }
  if (pipe2(from_child, O_CLOEXEC) != 0) {
    close(to_child[0]);
    close(to_child[1]);
    return absl::UnavailableError("cannot make a pipe");
  }
  absl::Cleanup close_ours = [&] {
    close(to_child[1]);
    close(from_child[0]);
  };
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, to_child[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, from_child[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclosefrom_np(&actions, 3);
  const std::string worker = ImportWorkerPath();
  char* argv[] = {const_cast<char*>(worker.c_str()), nullptr};
  char* no_environment[] = {nullptr};
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, worker.c_str(), &actions, nullptr, argv, no_environment);
  posix_spawn_file_actions_destroy(&actions);
  close(to_child[0]);
  close(from_child[1]);
  if (spawned != 0) {
    return absl::UnavailableError(
        absl::StrCat("cannot start the import worker ", worker, ": ", strerror(spawned)));
  }
  SendAll(to_child[1], job.SerializeAsString());
  shutdown(to_child[1], SHUT_WR);

  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(limits.wall_s));
  const Output output = ReadUntilClosed(from_child[0], deadline);
  if (output.timed_out || output.bytes.size() > kMaxOutcomeBytes) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (output.timed_out) return ForFile(path, absl::StrCat("took longer than ", limits.wall_s, " s"));
  if (output.bytes.size() > kMaxOutcomeBytes) return ForFile(path, "the imported mesh is too big");

  pb::ImportOutcome outcome;
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0) || !outcome.ParseFromString(output.bytes)) {
    return ForFile(path, Failure(status, limits));
  }
  if (outcome.has_error()) {
    // The worker names the file by the path it was given.
    std::string message = outcome.error().message();
    if (message.starts_with(job.path())) message.replace(0, job.path().size(), path);
    const int code = outcome.error().code();
    const bool known = code > 0 && code <= static_cast<int>(absl::StatusCode::kUnauthenticated);
    return absl::Status(known ? static_cast<absl::StatusCode>(code) : absl::StatusCode::kInvalidArgument,
                        message);
  }
  if (!outcome.has_mesh()) return ForFile(path, "the import worker sent nothing");
  absl::StatusOr<ImportedModel> model = MeshFromProto(outcome.mesh());
  if (!model.ok()) return ForFile(path, model.status().message());
  return model;
}

}  // namespace hs
