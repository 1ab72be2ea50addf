#include <dlfcn.h>

#include <span>
#include <string>

#include "render/gl/gl_api.h"
#include "sim/core/error.h"

namespace spume::gl {
namespace {

// Debian 12's libosmesa6; the unversioned name where only the development link is present.
constexpr const char* kLibraries[] = {"libOSMesa.so.8", "libOSMesa.so"};

}  // namespace

Functions load_functions(std::span<const char* const> libraries) {
  void* library = nullptr;
  const char* opened = nullptr;
  std::string errors;
  for (const char* name : libraries) {
    library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (library) {
      opened = name;
      break;
    }
    const char* why = dlerror();
    errors += str(errors.empty() ? "" : "; ", why ? why : name);
  }
  if (!library)
    fail("OSMesa, which draws the fluid's surface, could not be loaded (", errors,
         "); install it (Debian: apt-get install libosmesa6)");
  Functions f;
#define SPUME_GL_LOOKUP(name)                                                                      \
  f.p_##name = reinterpret_cast<decltype(f.p_##name)>(dlsym(library, #name));                      \
  if (!f.p_##name) {                                                                               \
    dlclose(library);                                                                              \
    fail("OSMesa: ", opened, " has no entry point " #name " (is it OSMesa? Debian: libosmesa6)"); \
  }
  SPUME_GL_FUNCTIONS(SPUME_GL_LOOKUP)
#undef SPUME_GL_LOOKUP
  return f;  // the library stays open for the process's life
}

const Functions& functions() {
  static const Functions loaded = load_functions(kLibraries);  // thread-safe; a failure is retried on the next call
  return loaded;
}

}  // namespace spume::gl
