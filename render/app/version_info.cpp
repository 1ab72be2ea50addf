#include "render/app/version_info.h"

#include <embree3/rtcore_config.h>
#include <GL/osmesa.h>
#include <LinearMath/btScalar.h>
#include <oneapi/tbb/version.h>

#include <Eigen/Core>

#include "sim/core/error.h"
#include "render/gl/osmesa_context.h"

namespace spume {
namespace {

constexpr const char* kCompiler =
#if defined(__clang__)
    "Clang " __clang_version__;
#elif defined(__GNUC__)
    "GCC " __VERSION__;
#else
    "unknown compiler";
#endif

// The Mesa that is loaded now (the shared library may differ from the headers built against).
std::string mesa_line() {
  try {
    // No rasteriser threads: the version query draws nothing, and llvmpipe crashes when the threads it
    // would start cannot (a small address space, ulimit -v).
    OsmesaOptions options;
    options.llvmpipe_threads = 0;
    const OsmesaContext context(1, 1, options);
    return str("Mesa:    ", context.version(), "; ", context.renderer());
  } catch (const Error& e) {
    return str("Mesa:    no OpenGL context (", e.what(), ")");
  }
}

}  // namespace

std::string version_text() {
  return str("spume ", SPUME_VERSION, "\n",                                                      //
             "build:   ", SPUME_BUILD_TYPE, ", ", kCompiler, ", C++ ", __cplusplus, "\n",           //
             "Embree:  ", RTC_VERSION_STRING, "\n",                                               //
             mesa_line(), " (OSMesa API ", OSMESA_MAJOR_VERSION, ".", OSMESA_MINOR_VERSION, ".",  //
             OSMESA_PATCH_VERSION, ")\n",                                                         //
             "Eigen:   ", EIGEN_WORLD_VERSION, ".", EIGEN_MAJOR_VERSION, ".", EIGEN_MINOR_VERSION, "\n",
             "oneTBB:  ", TBB_VERSION_STRING, " (loaded: ", TBB_runtime_version(), ")\n",  //
             "Bullet:  ", BT_BULLET_VERSION / 100, ".", BT_BULLET_VERSION % 100, "\n");
}

}  // namespace spume
