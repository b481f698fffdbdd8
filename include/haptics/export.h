#pragma once
// Marks what libhaptics_client exports: the library is built with hidden
// visibility, so that the gRPC, protobuf and Abseil inside it stay its own.

#if defined(HAPTICS_CLIENT_BUILDING)
#define HAPTICS_EXPORT __attribute__((visibility("default")))
#else
#define HAPTICS_EXPORT
#endif
