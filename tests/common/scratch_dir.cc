#include "tests/common/scratch_dir.h"

#include <unistd.h>

#include <cstdlib>
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
  // One plain name: an absolute path or ".." would put the directory, and
  // what remove_all then deletes, outside the scratch tree.
  const std::filesystem::path relative(name);
  if (name.empty() || relative.filename() != relative || name == "." || name == "..") std::abort();
  static ProcessScratch scratch;
  const std::filesystem::path dir = scratch.root / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace hs
