#include "sim/io/vdb_module.h"

#include <dlfcn.h>

#include "sim/core/error.h"

// Weak: defined only when the program links the module's code in (sim/io/vdb/module_api.cpp).
#pragma weak spume_vdb_module_api

namespace spume {
namespace {

const VdbModuleApi& checked(const VdbModuleApi* api, const std::string& where) {
  if (!api || api->layout != vdb_module_layout())
    fail(where, " is from another build of spume (its types differ from this program's); rebuild both "
         "(ninja -C build spume)");
  return *api;
}

const VdbModuleApi& open_module() {
  if (spume_vdb_module_api) return checked(spume_vdb_module_api(), "the linked-in OpenVDB code");
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path path = exe.parent_path() / kVdbModuleFile;
  const std::string help = str("; reading and writing .vdb files needs it beside the spume executable (",
                               exe.string(), "): 'ninja -C build spume' builds both, and a copy of spume "
                               "needs a copy of it");
  // The module is linked to bind its own symbols at load (-z now), so one this program lacks fails
  // here, named, not at first use; RTLD_LAZY leaves OpenVDB's thousands of functions to bind as used.
  void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
  if (!handle) fail("cannot open the OpenVDB module ", path.string(), ": ", dlerror(), help);
  using Entry = const VdbModuleApi* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, kVdbModuleEntry));
  if (!entry) fail("the OpenVDB module ", path.string(), " has no ", kVdbModuleEntry, help);
  return checked(entry(), path.string());
}

}  // namespace

const VdbModuleApi& vdb_module() {
  // Opened once for the process; a failed open throws and is tried again at the next call.
  static const VdbModuleApi& api = open_module();
  return api;
}

}  // namespace spume
