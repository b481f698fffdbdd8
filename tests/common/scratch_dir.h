#pragma once
// Scratch directories for the files tests write.

#include <filesystem>
#include <string_view>

namespace hs {

/// A fresh, empty directory named `name` (one plain name; anything else
/// aborts), under the test temp dir in a tree
/// of this process's own (so test processes run side by side never meet);
/// the tree is removed, with everything in it, when the process exits.
std::filesystem::path ScratchDir(std::string_view name);

}  // namespace hs
