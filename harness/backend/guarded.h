// Every backend operation runs its body through `guarded`, so that an exception from a driver
// wrapper (vk::raii throws, std::bad_alloc...) becomes an error naming the operation instead of
// leaving the seam.
#pragma once

#include <exception>
#include <string>

#include "base/result.h"

namespace xshade::harness {

// How an exception reads in an error after "<what>: ": e.what() unless a backend says more.
using DescribeException = std::string (*)(const std::exception&);
inline std::string exception_text(const std::exception& e) { return e.what(); }

template <class T, class F>
Result<T> guarded(const std::string& what, F&& body, DescribeException describe = &exception_text) {
  try {
    return body();
  } catch (const std::exception& e) {
    return fail(ErrorKind::Backend, what + ": " + describe(e));
  } catch (...) {
    return fail(ErrorKind::Backend, what + ": unknown exception");
  }
}

}  // namespace xshade::harness
