#include "tests/common/test_data_dir.h"

namespace hs {

std::string TestDataDir() { return HS_SOURCE_DIR "/tests/data"; }

std::string ScenesDir() { return HS_SOURCE_DIR "/scenes"; }

}  // namespace hs
