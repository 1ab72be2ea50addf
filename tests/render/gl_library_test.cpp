// OSMesa is opened when the first surface is drawn (render/gl/gl_library.cpp). When it cannot be, the
// error names every library tried, why each failed, and the Debian package to install; a library that
// opens but is not OSMesa is named with the first entry point it lacks. The real one gives them all.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "render/gl/gl_api.h"
#include "sim/core/error.h"
#include "tests/support/error_of.h"

namespace spume::gl {
namespace {

std::string error_of_loading(std::span<const char* const> libraries) {
  return testing::error_of([&] { load_functions(libraries); });
}

TEST(GlLibrary, AMissingLibraryIsNamedWithThePackageToInstall) {
  const std::array<const char*, 2> missing = {"libspume-no-such-osmesa.so.8", "libspume-no-such-osmesa.so"};
  const std::string e = error_of_loading(missing);
  EXPECT_NE(e.find("OSMesa, which draws the fluid's surface, could not be loaded"), std::string::npos) << e;
  EXPECT_NE(e.find("libspume-no-such-osmesa.so.8: cannot open shared object file"), std::string::npos) << e;
  EXPECT_NE(e.find("; libspume-no-such-osmesa.so: cannot open"), std::string::npos) << e;
  EXPECT_NE(e.find("apt-get install libosmesa6"), std::string::npos) << e;
}

TEST(GlLibrary, ALibraryThatIsNotOsmesaIsNamedWithTheEntryPointItLacks) {
  const std::array<const char*, 2> zlib = {"libspume-no-such-osmesa.so.8", "libz.so.1"};
  const std::string e = error_of_loading(zlib);
  // The list's first name, glActiveTexture, is the first looked up.
  EXPECT_NE(e.find("OSMesa: libz.so.1 has no entry point glActiveTexture"), std::string::npos) << e;
}

TEST(GlLibrary, DebiansOsmesaHasEveryEntryPoint) {
  const Functions& f = functions();
#define SPUME_GL_EXPECT(name) EXPECT_NE(reinterpret_cast<const void*>(f.p_##name), nullptr) << #name;
  SPUME_GL_FUNCTIONS(SPUME_GL_EXPECT)
#undef SPUME_GL_EXPECT
}

}  // namespace
}  // namespace spume::gl
