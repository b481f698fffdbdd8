#pragma once
// The haptic simulation service's client SDK (docs/sdk.md): link
// haptics::client (CMake: find_package(HapticsClient); pkg-config:
// haptics-client). The C API is haptics/client_c.h.

#include "haptics/device.h"
#include "haptics/error.h"
#include "haptics/frame.h"
#include "haptics/pose.h"
#include "haptics/session.h"
#include "haptics/version.h"
#include "haptics/watcher.h"
