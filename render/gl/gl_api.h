#pragma once
// The GL headers, included one way everywhere: OSMesa exports the core entry points (not the 4.5
// direct-state-access ones), so prototypes come from glext.h (no loader) and only -lOSMesa is linked.
// Private to render/gl/.
#define GL_GLEXT_PROTOTYPES 1
// clang-format off: glext.h needs the types from gl.h, which osmesa.h includes.
#include <GL/osmesa.h>
#include <GL/glext.h>
// clang-format on
