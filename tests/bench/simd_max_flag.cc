#include "tests/bench/simd_max_flag.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hwy/targets.h"

namespace hs {

bool TakeSimdMaxFlag(int& argc, char** argv, std::ostream& err) {
  constexpr std::string_view kFlag = "--simd_max=";
  int kept = 1;
  std::string_view name;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.starts_with(kFlag)) {
      name = arg.substr(kFlag.size());
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (name.empty()) return true;
  std::string names;
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    if (name == hwy::TargetName(target)) {
      // Highway's better targets have the lower bits.
      hwy::DisableTargets(target - 1);
      return true;
    }
    names += std::string(names.empty() ? "" : ", ") + hwy::TargetName(target);
  }
  err << "--simd_max: " << name << " is not a target this machine runs (" << names << ")\n";
  return false;
}

}  // namespace hs
