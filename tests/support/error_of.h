#pragma once
// The message of the error a piece of code is expected to throw: error_of(fn) for a spume::Error,
// error_of<UsageError>(fn) for a subclass. A test fails when fn throws nothing, or an Error that is
// not the expected kind.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <type_traits>
#include <typeinfo>

#include "sim/core/error.h"

namespace spume::testing {

template <typename Expected = Error>
std::string error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    if constexpr (std::is_same_v<Expected, Error>) {
      return e.what();
    } else {
      if (dynamic_cast<const Expected*>(&e) != nullptr) return e.what();
    }
    ADD_FAILURE() << "an Error that is not a " << typeid(Expected).name() << ": " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected a " << typeid(Expected).name() << ", nothing was thrown";
  return "";
}

}  // namespace spume::testing
