// EGL backend: the device platform (EGL_EXT_platform_device: how an NVIDIA GPU is reached without X),
// hardware devices before software ones, then Mesa's surfaceless platform. The context is current with no
// surface (EGL_KHR_surfaceless_context) and, where offered, no config (EGL_KHR_no_config_context).
#include "gl_info.hpp"
#include "gpu_backends.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <vector>

namespace dqskin::gpu {
namespace {

const char* egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "EGL error";
  }
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Client extensions, queried once.
struct ClientExtensions {
  bool platform_base = false, platform_device = false, device_enumeration = false, platform_surfaceless = false;
  explicit ClientExtensions(const char* list)
      : platform_base(has_extension(list, "EGL_EXT_platform_base")),
        platform_device(has_extension(list, "EGL_EXT_platform_device")),
        device_enumeration(has_extension(list, "EGL_EXT_device_enumeration") || has_extension(list, "EGL_EXT_device_base")),
        platform_surfaceless(has_extension(list, "EGL_MESA_platform_surfaceless")) {}
};

class EglContext final : public GpuContext {
public:
  EglContext(EGLDisplay display, EGLContext context, const char* backend) : display_(display), context_(context) {
    info_.backend = backend;
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void make_current() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_); }
  void* proc_address(const char* name) const override { return reinterpret_cast<void*>(eglGetProcAddress(name)); }
  GpuContextInfo& mutable_info() { return info_; }

private:
  EGLDisplay display_;
  EGLContext context_;
};

void* egl_loader(const char* name, const void*) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

// Initialises `display` and makes a 4.3 core context current on it, or says why not.
std::unique_ptr<GpuContext> try_display(EGLDisplay display, const char* backend, std::string& why) {
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY) {
    why = std::string("no display (") + egl_error_name(eglGetError()) + ")";
    return nullptr;
  }
  if (!eglInitialize(display, &major, &minor)) {
    why = std::string("eglInitialize failed (") + egl_error_name(eglGetError()) + ")";
    return nullptr;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    why = "no EGL_KHR_surfaceless_context";
    eglTerminate(display);
    return nullptr;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = std::string("no desktop OpenGL (") + egl_error_name(eglGetError()) + ")";
    eglTerminate(display);
    return nullptr;
  }
  EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR
  if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, wanted, &config, 1, &count) || count == 0) {
      why = "no OpenGL config";
      eglTerminate(display);
      return nullptr;
    }
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    why = std::string("no OpenGL 4.3 core context (") + egl_error_name(eglGetError()) + ")";
    eglTerminate(display);
    return nullptr;
  }
  auto result = std::make_unique<EglContext>(display, context, backend);
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    why = std::string("eglMakeCurrent failed (") + egl_error_name(eglGetError()) + ")";
    return nullptr;
  }
  why = query_gl(&egl_loader, nullptr, result->mutable_info());
  if (!why.empty()) return nullptr;
  return result;
}

using QueryDevices = EGLBoolean (*)(EGLint, EGLDeviceEXT*, EGLint*);
using GetPlatformDisplay = EGLDisplay (*)(EGLenum, void*, const EGLint*);
using QueryDeviceString = const char* (*)(EGLDeviceEXT, EGLint);

}  // namespace

std::unique_ptr<GpuContext> create_egl_context(std::string& report, bool hardware_only) {
  const ClientExtensions client(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS));
  const auto get_platform_display = reinterpret_cast<GetPlatformDisplay>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::string why;

  if (client.platform_base && client.platform_device && client.device_enumeration && get_platform_display) {
    const auto query_devices = reinterpret_cast<QueryDevices>(eglGetProcAddress("eglQueryDevicesEXT"));
    const auto query_string = reinterpret_cast<QueryDeviceString>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLint count = 0;
    std::vector<EGLDeviceEXT> devices;
    if (query_devices && query_devices(0, nullptr, &count) && count > 0) {
      devices.resize(size_t(count));
      query_devices(count, devices.data(), &count);
      devices.resize(size_t(count));
    }
    // Hardware first: Mesa lists its software rasterizer as a device too (EGL_MESA_device_software).
    for (const bool software : {false, true}) {
      if (software && hardware_only) break;
      for (size_t i = 0; i < devices.size(); ++i) {
        const char* ext = query_string ? query_string(devices[i], EGL_EXTENSIONS) : nullptr;
        if (has_extension(ext, "EGL_MESA_device_software") != software) continue;
        if (auto ctx = try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "egl-device", why)) {
          if (hardware_only && !ctx->info().hardware) continue;
          return ctx;
        }
        report += "egl-device " + std::to_string(i) + ": " + why + "; ";
      }
    }
    if (devices.empty()) report += "egl-device: no devices; ";
  } else {
    report += "egl-device: EGL_EXT_platform_device not offered; ";
  }

  if (hardware_only) return nullptr;
  if (client.platform_surfaceless && get_platform_display) {
    if (auto ctx = try_display(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                               "egl-surfaceless", why))
      return ctx;
    report += "egl-surfaceless: " + why + "; ";
  } else {
    report += "egl-surfaceless: EGL_MESA_platform_surfaceless not offered; ";
  }
  return nullptr;
}

}  // namespace dqskin::gpu
