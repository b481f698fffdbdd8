#pragma once
// The one name of each object kind that clients print and send on (scene
// listings, the viewer's geometry).

#include "haptics/v1/scene.pb.h"

namespace hs {

/// "fixed", "tool" or "free"; "unspecified" for a kind the server never
/// sends (it refuses OBJECT_KIND_UNSPECIFIED) or one this build does not
/// know.
const char* ObjectKindName(haptics::v1::ObjectKind kind);

}  // namespace hs
