#pragma once
// haptics.v1.Frame as the SDK's plain Frame (haptics/frame.h).

#include "haptics/frame.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::sdk {

haptics::Frame FrameFromProto(const haptics::v1::Frame& frame);

}  // namespace hs::sdk
