#pragma once
// The one owner of the off-screen OpenGL context: OSMesa (Mesa's llvmpipe), a 4.5 core profile, made
// current on our own RGBA8 buffer. Create it once per run and reuse it across frames; it is current
// on the thread that created it (use it from that thread only). The surface pass renders into its
// own framebuffer objects; this buffer is the drawable OSMesa requires.
#include <cstdint>
#include <string>
#include <vector>

namespace spume {

struct OsmesaOptions {
  // llvmpipe rasteriser threads (LP_NUM_THREADS): -1 leaves the environment alone (default: one per
  // CPU); 0 rasterises on the calling thread. Mesa reads it once, when the first context of the
  // process is created, so later contexts ignore a different value (see gl_determinism_test).
  int llvmpipe_threads = -1;
};

class OsmesaContext {
 public:
  // Throws Error when OSMesa cannot make a core-profile context of at least GL 4.5.
  OsmesaContext(int width, int height, const OsmesaOptions& options = {});
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  // Binds the context to a buffer of this size and makes it current on the calling thread.
  void make_current(int width, int height);
  // Makes it current again if another context took over (cheap when it is already current).
  void ensure_current();
  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER, e.g. "llvmpipe (LLVM 15, 256 bits)"
  const std::string& version() const { return version_; }

 private:
  void* context_ = nullptr;  // OSMesaContext
  int width_ = 0, height_ = 0;
  std::vector<uint8_t> buffer_;  // RGBA8, the context's drawable
  std::string renderer_, version_;
};

// Throws Error naming `where` when the GL error flag is set (drains all pending errors).
void check_gl(const char* where);

}  // namespace spume
