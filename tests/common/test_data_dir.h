#pragma once
// Where the tests find the checkout's files. The path is compiled into
// test_data_dir.cc alone: as a definition on every test it would sit in
// their command lines, and no test compiled in one clone would be found in
// ccache by the build of another.

#include <string>
#include <string_view>

namespace hs {

/// The absolute path of tests/data in the checkout.
std::string TestDataDir();

/// The absolute path of tests/data/`name`.
std::string TestDataPath(std::string_view name);

/// The absolute path of scenes/ in the checkout.
std::string ScenesDir();

}  // namespace hs
