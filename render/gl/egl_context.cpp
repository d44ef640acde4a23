// SPDX-License-Identifier: BSD-3-Clause
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <vector>

#include "render/gl/gl_context.h"

namespace voxlink::render::gl {
namespace {

class EglContext : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void makeCurrent() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
  }

 private:
  EGLDisplay display_;
  EGLContext context_;
};

bool hasClientExtension(const char* name) {
  const char* all = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  return all && epoxy_extension_in_string(all, name);
}

// Displays to try, best first.
std::vector<EGLDisplay> candidateDisplays() {
  std::vector<EGLDisplay> out;
  if (hasClientExtension("EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back(d);
  }
  if (hasClientExtension("EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (eglQueryDevicesEXT(8, devices, &count))
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) out.push_back(d);
      }
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY) out.push_back(d);
  return out;
}

}  // namespace

std::string GlContext::description() const {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + " | " + (version ? version : "?");
}

Result<std::unique_ptr<GlContext>> createHeadlessContext() {
  std::string tried;
  for (EGLDisplay display : candidateDisplays()) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      tried += cat(" eglInitialize failed (0x", std::hex, eglGetError(), ");");
      continue;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      tried += " no desktop OpenGL API;";
      eglTerminate(display);
      continue;
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
      tried += cat(" no GL 4.5 core context (0x", std::hex, eglGetError(), ");");
      eglTerminate(display);
      continue;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      tried += cat(" surfaceless eglMakeCurrent failed (0x", std::hex, eglGetError(), ");");
      eglDestroyContext(display, context);
      eglTerminate(display);
      continue;
    }
    auto result = std::make_unique<EglContext>(display, context);
    VOXLINK_RETURN_IF_ERROR(checkGlCapabilities());
    return std::unique_ptr<GlContext>(std::move(result));
  }
  return makeError(ErrorCode::kUnsupported, "EGL: no headless OpenGL 4.5 context:",
                   tried.empty() ? " no EGL display" : tried);
}

Status checkGlCapabilities() {
  if (epoxy_gl_version() < 43)
    return makeError(ErrorCode::kUnsupported, "OpenGL ", epoxy_gl_version() / 10, ".",
                     epoxy_gl_version() % 10, ": compute shaders need 4.3 or later");
  return Status::ok();
}

}  // namespace voxlink::render::gl
