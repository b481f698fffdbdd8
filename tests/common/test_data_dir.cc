#include "tests/common/test_data_dir.h"

namespace hs {

std::string TestDataDir() { return HS_SOURCE_DIR "/tests/data"; }

std::string TestDataPath(std::string_view name) { return TestDataDir() + "/" + std::string(name); }

std::string ScenesDir() { return HS_SOURCE_DIR "/scenes"; }

}  // namespace hs
