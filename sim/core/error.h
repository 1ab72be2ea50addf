#pragma once
// One error type for every bad input: the message names where (file, key path, frame, particle),
// what was found and what is allowed. Context is prepended as the error rises through stages.
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace spume {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Concatenate anything streamable into a string: str("frame ", 3, ": ", x).
template <typename... Parts>
std::string str(Parts&&... parts) {
  std::ostringstream out;
  (out << ... << std::forward<Parts>(parts));
  return out.str();
}

template <typename... Parts>
[[noreturn]] void fail(Parts&&... parts) {
  throw Error(str(std::forward<Parts>(parts)...));
}

// Run fn; if it throws an Error, rethrow with "context: " in front so the user sees the whole chain.
template <typename Fn>
decltype(auto) with_context(const std::string& context, Fn&& fn) {
  try {
    return std::forward<Fn>(fn)();
  } catch (const Error& e) {
    throw Error(context + ": " + e.what());
  }
}

}  // namespace spume
