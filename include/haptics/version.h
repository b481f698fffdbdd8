#pragma once
// The SDK's version: MAJOR changes break the C ABI or the C++ API.

#define HAPTICS_CLIENT_VERSION_MAJOR 1
#define HAPTICS_CLIENT_VERSION_MINOR 3
#define HAPTICS_CLIENT_VERSION_PATCH 0
