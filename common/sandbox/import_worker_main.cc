// haptic-import: imports one model file for a parent that does not trust
// it (common/sandbox/sandboxed_import.h). Reads an ImportJob on stdin,
// limits itself, reads the file, shuts itself off from files, sockets and
// programs, imports the bytes and writes an ImportOutcome on stdout.
// Exits 0 with an outcome; anything else (a crash, a limit hit) is the
// parent's to report.

#include <errno.h>
#include <fcntl.h>
#include <seccomp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "common/model/import.h"
#include "common/sandbox/import_codec.h"

// Under AddressSanitizer or ThreadSanitizer (scripts/sanitize.sh) the
// shadow memory takes terabytes of address space, and LeakSanitizer's
// check at exit reads /proc, which the filter refuses: such builds set no
// address-space limit and check no leaks here. A fault inside a reader
// stays a signal, as without ASan (the parent reports it as a crash), and
// an error ASan finds aborts: the worker gets no environment, so its
// options are compiled in.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define HS_SANITIZED_BUILD 1
extern "C" const char* __asan_default_options() {
  return "detect_leaks=0:handle_segv=0:handle_sigbus=0:handle_sigfpe=0:abort_on_error=1";
}
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define HS_SANITIZED_BUILD 1
#endif

namespace {

namespace pb = haptics::internal;

#ifdef HS_SANITIZED_BUILD
constexpr bool kLimitAddressSpace = false;
#else
constexpr bool kLimitAddressSpace = true;
#endif

void Limit(int resource, rlim_t value) {
  const rlimit limit{value, value};
  setrlimit(resource, &limit);
}

// From here on, opening, creating or looking up a file, a socket or a
// process fails with EACCES, and running a program kills the worker. libseccomp writes
// the BPF program; the list is of what a reader has no business doing.
bool ShutOffTheWorld() {
  scmp_filter_ctx filter = seccomp_init(SCMP_ACT_ALLOW);
  if (filter == nullptr) return false;
  bool ok = true;
  for (int call : {SCMP_SYS(open),
                   SCMP_SYS(openat),
                   SCMP_SYS(openat2),
                   SCMP_SYS(creat),
                   SCMP_SYS(open_by_handle_at),
                   SCMP_SYS(socket),
                   SCMP_SYS(socketpair),
                   SCMP_SYS(connect),
                   SCMP_SYS(bind),
                   SCMP_SYS(listen),
                   SCMP_SYS(accept),
                   SCMP_SYS(accept4),
                   SCMP_SYS(fork),
                   SCMP_SYS(vfork),
                   SCMP_SYS(ptrace),
                   SCMP_SYS(unlink),
                   SCMP_SYS(unlinkat),
                   SCMP_SYS(rename),
                   SCMP_SYS(renameat),
                   SCMP_SYS(renameat2),
                   SCMP_SYS(mkdir),
                   SCMP_SYS(mkdirat),
                   SCMP_SYS(truncate),
                   SCMP_SYS(chmod),
                   SCMP_SYS(fchmodat),
                   SCMP_SYS(link),
                   SCMP_SYS(symlink)}) {
    ok = ok && seccomp_rule_add(filter, SCMP_ACT_ERRNO(EACCES), call, 0) == 0;
  }
  // Nor may it ask whether a path exists (Coin stats a File node's name
  // before opening it): stat-like calls on a path fail too, while fstat
  // (newfstatat and statx on a descriptor, AT_EMPTY_PATH) still works.
  for (int call : {SCMP_SYS(stat), SCMP_SYS(lstat), SCMP_SYS(access), SCMP_SYS(faccessat),
                   SCMP_SYS(faccessat2), SCMP_SYS(readlink), SCMP_SYS(readlinkat), SCMP_SYS(chdir),
                   SCMP_SYS(getdents64)}) {
    ok = ok && seccomp_rule_add(filter, SCMP_ACT_ERRNO(EACCES), call, 0) == 0;
  }
  ok = ok && seccomp_rule_add(filter, SCMP_ACT_ERRNO(EACCES), SCMP_SYS(newfstatat), 1,
                              SCMP_A3(SCMP_CMP_MASKED_EQ, AT_EMPTY_PATH, 0)) == 0;
  ok = ok && seccomp_rule_add(filter, SCMP_ACT_ERRNO(EACCES), SCMP_SYS(statx), 1,
                              SCMP_A2(SCMP_CMP_MASKED_EQ, AT_EMPTY_PATH, 0)) == 0;
  for (int call : {SCMP_SYS(execve), SCMP_SYS(execveat)}) {
    ok = ok && seccomp_rule_add(filter, SCMP_ACT_KILL_PROCESS, call, 0) == 0;
  }
  ok = ok && seccomp_load(filter) == 0;
  seccomp_release(filter);
  return ok;
}

int Answer(const pb::ImportOutcome& outcome) {
  return outcome.SerializeToOstream(&std::cout) && std::cout.flush() ? 0 : 1;
}

int Fail(absl::StatusCode code, const std::string& message) {
  pb::ImportOutcome outcome;
  outcome.mutable_error()->set_code(static_cast<int>(code));
  outcome.mutable_error()->set_message(message);
  return Answer(outcome);
}

}  // namespace

int main() {
  pb::ImportJob job;
  if (!job.ParseFromIstream(&std::cin)) return Fail(absl::StatusCode::kInternal, "bad job");
  Limit(RLIMIT_CPU, static_cast<rlim_t>(std::max(1.0, job.cpu_s())));
  if (kLimitAddressSpace) Limit(RLIMIT_AS, static_cast<rlim_t>(job.memory_bytes()));
  Limit(RLIMIT_STACK, static_cast<rlim_t>(job.stack_bytes()));
  Limit(RLIMIT_FSIZE, 0);
  Limit(RLIMIT_CORE, 0);

  std::string bytes;
  {
    std::ifstream in(job.path(), std::ios::binary);
    if (!in) return Fail(absl::StatusCode::kNotFound, job.path() + ": cannot open it");
    std::ostringstream text;
    text << in.rdbuf();
    bytes = text.str();
  }
  hs::PrepareReaders();
  if (!ShutOffTheWorld()) return Fail(absl::StatusCode::kInternal, "cannot install the filter");

  absl::StatusOr<hs::ImportedModel> model =
      hs::ImportModelBytes(bytes, job.path(), hs::OptionsFromJob(job));
  if (!model.ok()) return Fail(model.status().code(), std::string(model.status().message()));
  pb::ImportOutcome outcome;
  *outcome.mutable_mesh() = hs::MeshToProto(*model);
  return Answer(outcome);
}
