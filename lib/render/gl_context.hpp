// A headless OpenGL 3.3 core context through EGL, without a window system:
//   gpu  - the EGL device platform (EGL_EXT_platform_device), first device
//          that is not Mesa's software device (NVIDIA, AMD, Intel);
//   cpu  - Mesa's software device (llvmpipe), else the surfaceless platform
//          (EGL_MESA_platform_surfaceless);
//   auto - gpu when one answers, else cpu.
// The context renders into framebuffer objects only.
#pragma once
#include <memory>
#include <string>

namespace rscene::render {

enum class Backend { Auto, Gpu, Cpu };

struct ContextInfo {
  std::string backend;   // "gpu" or "cpu"
  std::string platform;  // "device" or "surfaceless"
  std::string device;    // EGL device extensions / DRM node, when known
  std::string eglVendor;
  std::string vendor, renderer, version;  // GL strings
};

class GlContext {
 public:
  // nullptr and `error` set when no context could be made.
  static std::unique_ptr<GlContext> create(Backend backend, std::string* error);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;
  const ContextInfo& info() const { return info_; }
  // An EGL context is current on one thread at a time: a program that
  // draws from several threads (the Python package) makes it current on
  // the drawing thread first, and releases it after.  create() leaves it
  // current on the creating thread.  False when EGL refuses.
  bool makeCurrent() const;
  void release() const;

 private:
  GlContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  ContextInfo info_;
};

}  // namespace rscene::render
