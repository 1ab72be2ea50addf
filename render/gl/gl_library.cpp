#include <dlfcn.h>

#include <string>

#include "render/gl/gl_api.h"
#include "sim/core/error.h"

namespace spume::gl {
namespace {

// Debian 12's libosmesa6; the unversioned name where only the development link is present.
constexpr const char* kLibraries[] = {"libOSMesa.so.8", "libOSMesa.so"};

Functions open_library() {
  void* library = nullptr;
  std::string errors;
  for (const char* name : kLibraries) {
    library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (library) break;
    const char* why = dlerror();
    errors += str(errors.empty() ? "" : "; ", why ? why : name);
  }
  if (!library)
    fail("OSMesa, which draws the fluid's surface, could not be loaded (", errors,
         "); install it (Debian: apt-get install libosmesa6)");
  Functions f;
#define SPUME_GL_LOOKUP(name)                                                          \
  f.p_##name = reinterpret_cast<decltype(f.p_##name)>(dlsym(library, #name));          \
  if (!f.p_##name) fail("OSMesa: ", kLibraries[0], " has no entry point " #name);
  SPUME_GL_FUNCTIONS(SPUME_GL_LOOKUP)
#undef SPUME_GL_LOOKUP
  return f;  // the library stays open for the process's life
}

}  // namespace

const Functions& functions() {
  static const Functions loaded = open_library();  // thread-safe; a failure is retried on the next call
  return loaded;
}

}  // namespace spume::gl
