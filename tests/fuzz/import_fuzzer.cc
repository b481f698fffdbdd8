// libFuzzer target: bytes into the importers, as the haptic-import worker
// runs them (ImportModelBytes). The first byte picks the format, the rest
// is the file. Inputs are kept short (-max_len) so that nesting stays
// within the stack: deeper files are the worker's to crash on, and
// sandboxed_import_test shows they do no harm.

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/model/import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kFormats[] = {"obj", "stl", "ply", "off", "dxf", "gltf", "glb",
                                         "3ds", "dae", "iv",  "wrl", "x",   "fbx"};
  if (size < 1) return 0;
  const std::string name =
      std::string("fuzz.") + kFormats[data[0] % (sizeof kFormats / sizeof *kFormats)];
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  (void)hs::ImportModelBytes(bytes, name);
  return 0;
}
