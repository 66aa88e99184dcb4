// For the front end's tests that hostile input cannot make it hang: the bound such a test holds a
// compile to is generous for an optimised build, and scaled for builds that are several times
// slower (sanitizers, no optimisation). A test file includes this; nothing else does.
#pragma once

#include <chrono>

#ifndef __has_feature
#define __has_feature(x) 0
#endif

namespace xshade::hlsl {

// XSHADE_SANITIZED_BUILD: the libraries are instrumented, though a test program itself is not.
#if defined(XSHADE_SANITIZED_BUILD) || defined(__SANITIZE_ADDRESS__) || __has_feature(address_sanitizer) || \
    !defined(NDEBUG)
inline constexpr double kTimeScale = 10;
#else
inline constexpr double kTimeScale = 1;
#endif

// The seconds since `start`, for a test to hold against its bound.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace xshade::hlsl
