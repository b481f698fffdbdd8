#include "common/api/object_kind_name.h"

namespace hs {

const char* ObjectKindName(haptics::v1::ObjectKind kind) {
  switch (kind) {
    case haptics::v1::OBJECT_KIND_FIXED:
      return "fixed";
    case haptics::v1::OBJECT_KIND_TOOL:
      return "tool";
    case haptics::v1::OBJECT_KIND_FREE:
      return "free";
    default:
      return "unspecified";
  }
}

}  // namespace hs
