#pragma once
// Whether this test binary is built under a sanitizer (ASan or TSan, with
// gcc's or clang's spelling): oracle loops run fewer cases there, as each
// costs ten times more, and a few checks that the sanitizers' own runtime
// defeats are skipped.

namespace hs::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

}  // namespace hs::testing
