#pragma once
// The files of one recorded session: `<scene>_<start, UTC>.<part>.hsrec`,
// part 000 first, the next part when the size cap rolls a file over.

#include <cstdint>
#include <string>
#include <vector>

namespace hs {

/// The file name of part `part` of the session of `scene` that began at
/// `start_unix_ns`, e.g. "demo_20261124T230501.123Z.000.hsrec" (spaces in
/// the scene's name become '_').
std::string SessionFileName(const std::string& scene, int64_t start_unix_ns, int part);

/// `file` and the parts of its session after it that exist, in order. A
/// name not of SessionFileName's form is a session of one file.
std::vector<std::string> SessionParts(const std::string& file);

}  // namespace hs
