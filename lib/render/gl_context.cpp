#include "render/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstring>
#include <vector>

namespace rscene::render {
namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)); p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string eglErrorText(const char* what) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04x)", what, eglGetError());
  return buf;
}

struct Candidate {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string backend, platform, device;
};

// Devices of the EGL device platform, split into hardware and software.
void enumerateDevices(std::vector<Candidate>& gpu, std::vector<Candidate>& cpu) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(client, "EGL_EXT_device_enumeration") || !hasExtension(client, "EGL_EXT_platform_device")) return;
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto deviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  auto platformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!queryDevices || !deviceString || !platformDisplay) return;
  EGLint count = 0;
  if (!queryDevices(0, nullptr, &count) || count <= 0) return;
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (!queryDevices(count, devices.data(), &count)) return;
  for (EGLint i = 0; i < count; ++i) {
    const char* ext = deviceString(devices[std::size_t(i)], EGL_EXTENSIONS);
    Candidate c;
    c.platform = "device";
    c.display = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
    c.device = "device " + std::to_string(i);
    if (hasExtension(ext, "EGL_EXT_device_drm")) {
      const char* node = deviceString(devices[std::size_t(i)], EGL_DRM_DEVICE_FILE_EXT);
      if (node) c.device += std::string(" (") + node + ")";
    }
    bool software = hasExtension(ext, "EGL_MESA_device_software");
    c.backend = software ? "cpu" : "gpu";
    if (c.display != EGL_NO_DISPLAY) (software ? cpu : gpu).push_back(c);
  }
}

Candidate surfaceless() {
  Candidate c;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(client, "EGL_MESA_platform_surfaceless")) return c;
  auto platformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!platformDisplay) return c;
  c.display = platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  c.backend = "cpu";
  c.platform = "surfaceless";
  return c;
}

}  // namespace

std::unique_ptr<GlContext> GlContext::create(Backend backend, std::string* error) {
  std::vector<Candidate> gpu, cpu;
  enumerateDevices(gpu, cpu);
  std::vector<Candidate> order;
  if (backend != Backend::Cpu) order.insert(order.end(), gpu.begin(), gpu.end());
  if (backend != Backend::Gpu) {
    order.insert(order.end(), cpu.begin(), cpu.end());
    Candidate s = surfaceless();
    if (s.display != EGL_NO_DISPLAY) order.push_back(s);
  }
  std::string lastError = backend == Backend::Gpu ? "no GPU EGL device found" : "no EGL display available";
  for (Candidate& c : order) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(c.display, &major, &minor)) {
      lastError = eglErrorText("eglInitialize");
      continue;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      lastError = eglErrorText("eglBindAPI(OpenGL)");
      eglTerminate(c.display);
      continue;
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    // Configless contexts (EGL_KHR_no_config_context) need no surface type.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(eglQueryString(c.display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
      const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint n = 0;
      if (!eglChooseConfig(c.display, wanted, &config, 1, &n) || n == 0) {
        lastError = eglErrorText("eglChooseConfig");
        eglTerminate(c.display);
        continue;
      }
    }
    EGLContext ctx = eglCreateContext(c.display, config, EGL_NO_CONTEXT, attributes);
    if (ctx == EGL_NO_CONTEXT) {
      lastError = eglErrorText("eglCreateContext(OpenGL 3.3 core)");
      eglTerminate(c.display);
      continue;
    }
    if (!eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
      lastError = eglErrorText("eglMakeCurrent");
      eglDestroyContext(c.display, ctx);
      eglTerminate(c.display);
      continue;
    }
    std::unique_ptr<GlContext> out(new GlContext());
    out->display_ = c.display;
    out->context_ = ctx;
    auto str = [](GLenum e) {
      const GLubyte* s = glGetString(e);
      return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    out->info_ = ContextInfo{c.backend, c.platform, c.device, eglQueryString(c.display, EGL_VENDOR) ?: "",
                             str(GL_VENDOR), str(GL_RENDERER), str(GL_VERSION)};
    // A driver that calls itself llvmpipe/softpipe is the CPU, whatever platform it came through.
    if (out->info_.renderer.find("llvmpipe") != std::string::npos ||
        out->info_.renderer.find("softpipe") != std::string::npos)
      out->info_.backend = "cpu";
    if (backend == Backend::Gpu && out->info_.backend != "gpu") {
      lastError = "EGL device renders on the CPU (" + out->info_.renderer + ")";
      continue;  // the destructor releases it
    }
    return out;
  }
  if (error) *error = lastError;
  return nullptr;
}

bool GlContext::makeCurrent() const {
  return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_)) == EGL_TRUE;
}

void GlContext::release() const { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

namespace detail {
void forgetPrograms(void* eglContext);  // renderer.cpp
}

GlContext::~GlContext() {
  if (!display_) return;
  detail::forgetPrograms(context_);
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_) eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

}  // namespace rscene::render
