#include "sim/io/library_abort_guard.h"

namespace spume {
namespace {

thread_local const char* t_message = nullptr;

}  // namespace

LibraryAbortGuard::LibraryAbortGuard(const std::string& message) : outer_(t_message), message_(message) {
  t_message = message_.c_str();
}

LibraryAbortGuard::~LibraryAbortGuard() { t_message = outer_; }

const char* library_abort_message() { return t_message; }

}  // namespace spume
