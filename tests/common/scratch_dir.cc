#include "tests/common/scratch_dir.h"

#include <unistd.h>

#include <string>
#include <system_error>

#include "gtest/gtest.h"

namespace hs {
namespace {

struct ProcessScratch {
  const std::filesystem::path root =
      std::filesystem::path(::testing::TempDir()) / ("hs_test_" + std::to_string(getpid()));
  ~ProcessScratch() {
    std::error_code ignored;  // nothing to do about a file that will not go
    std::filesystem::remove_all(root, ignored);
  }
};

}  // namespace

std::filesystem::path ScratchDir(std::string_view name) {
  static ProcessScratch scratch;
  const std::filesystem::path dir = scratch.root / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace hs
