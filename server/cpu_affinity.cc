#include "server/cpu_affinity.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <string>

#include "absl/algorithm/container.h"
#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"

namespace hs {
namespace {

// Written here: glibc reads no CPU list, and the libraries that do
// (libnuma, hwloc) would be a dependency for a dozen lines.
absl::StatusOr<int> ParseCpu(absl::string_view text, absl::string_view list) {
  int cpu = -1;
  const bool digits_only = !text.empty() && absl::c_all_of(text, absl::ascii_isdigit);
  if (!digits_only || !absl::SimpleAtoi(text, &cpu) || cpu >= CPU_SETSIZE) {
    return absl::InvalidArgumentError(absl::StrCat(
        "'", list, "' is no CPU list: '", text, "' is no CPU number (0 to ", CPU_SETSIZE - 1, ")"));
  }
  return cpu;
}

void CpuFree(cpu_set_t* set) { CPU_FREE(set); }

}  // namespace

absl::StatusOr<std::vector<int>> ParseCpuList(absl::string_view text) {
  std::vector<int> cpus;
  for (absl::string_view item : absl::StrSplit(text, ',')) {
    const std::vector<absl::string_view> ends = absl::StrSplit(item, absl::MaxSplits('-', 1));
    absl::StatusOr<int> first = ParseCpu(ends[0], text);
    if (!first.ok()) return first.status();
    absl::StatusOr<int> last = ends.size() == 2 ? ParseCpu(ends[1], text) : first;
    if (!last.ok()) return last.status();
    if (*last < *first) {
      return absl::InvalidArgumentError(
          absl::StrCat("'", text, "' is no CPU list: the range '", item, "' runs backwards"));
    }
    for (int cpu = *first; cpu <= *last; ++cpu) cpus.push_back(cpu);
  }
  std::sort(cpus.begin(), cpus.end());
  cpus.erase(std::unique(cpus.begin(), cpus.end()), cpus.end());
  return cpus;
}

std::vector<int> AllowedCpus() {
  // Sized for the machine: a fixed cpu_set_t (CPU_SETSIZE) is refused
  // (EINVAL) by a kernel configured for more CPUs.
  const int count = std::max<int>(CPU_SETSIZE, static_cast<int>(sysconf(_SC_NPROCESSORS_CONF)));
  std::unique_ptr<cpu_set_t, decltype(&CpuFree)> set(CPU_ALLOC(count), &CpuFree);
  const size_t bytes = CPU_ALLOC_SIZE(count);
  std::vector<int> cpus;
  if (set == nullptr) return cpus;
  CPU_ZERO_S(bytes, set.get());
  if (sched_getaffinity(0, bytes, set.get()) != 0) return cpus;
  for (int cpu = 0; cpu < count; ++cpu) {
    if (CPU_ISSET_S(cpu, bytes, set.get())) cpus.push_back(cpu);
  }
  return cpus;
}

absl::Status CheckCpusAllowed(const std::vector<int>& cpus) {
  if (cpus.empty()) return absl::InvalidArgumentError("no CPU given");
  const std::vector<int> allowed = AllowedCpus();
  for (const int cpu : cpus) {
    if (!std::binary_search(allowed.begin(), allowed.end(), cpu)) {
      return absl::InvalidArgumentError(absl::StrCat(
          "CPU ", cpu, " is not one this process may run on (", absl::StrJoin(allowed, ","), ")"));
    }
  }
  return absl::OkStatus();
}

absl::Status RunOnCpus(const std::vector<int>& cpus) {
  if (absl::Status s = CheckCpusAllowed(cpus); !s.ok()) return s;
  cpu_set_t set;
  CPU_ZERO(&set);
  for (const int cpu : cpus) CPU_SET(cpu, &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0) {
    return absl::InternalError(absl::StrCat("sched_setaffinity: ", std::strerror(errno)));
  }
  return absl::OkStatus();
}

}  // namespace hs
