// The EGL backend: a hardware device through EGL_EXT_platform_device when there is one, else Mesa's surfaceless
// platform (llvmpipe). Contexts are surfaceless: no default framebuffer, the stages render into FBOs and SSBOs.
// libEGL is dlopen'ed the first time EGL is chosen and its functions reach us through glad's EGL loader, so the
// stages do not link it: on a machine without libEGL they still start, and say so in one line (or run on OSMesa).
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>

#include <glad/egl.h>

#include "context_backend.h"

namespace rt::gpu {

namespace {

bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// Opens libEGL once per process (it stays loaded, as libOSMesa does) and fills glad's EGL function pointers: a
// function libEGL exports by name comes from dlsym, an extension's (eglQueryDevicesEXT) from eglGetProcAddress.
// RT_EGL_LIBRARY names another libEGL (the tests name a missing one). Throws saying why it cannot.
void load_egl() {
    static void* lib = nullptr;
    if (lib) return;
    const char* override = std::getenv("RT_EGL_LIBRARY");
    const std::string name = override && *override ? override : "libEGL.so.1";
    void* opened = open_backend_library("EGL", name);
    // glad reads the EGL version and extensions from eglGetDisplay(EGL_DEFAULT_DISPLAY) when given no display, and
    // an uninitialised display answers neither (glad would then take EGL 1.0 and skip eglGetPlatformDisplay). So
    // while glad loads, eglGetDisplay answers EGL_NO_DISPLAY: glad then asks EGL_NO_DISPLAY, which in EGL 1.5 gives
    // the client's version and client extensions, the ones choosing a platform display needs. It is put back after.
    auto load = [](void* handle, const char* fn) -> GLADapiproc {
        if (std::strcmp(fn, "eglGetDisplay") == 0)
            return reinterpret_cast<GLADapiproc>(+[](EGLNativeDisplayType) { return EGL_NO_DISPLAY; });
        if (void* p = dlsym(handle, fn)) return reinterpret_cast<GLADapiproc>(p);
        auto get_proc = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(handle, "eglGetProcAddress"));
        return get_proc ? reinterpret_cast<GLADapiproc>(get_proc(fn)) : nullptr;
    };
    const int version = gladLoadEGLUserPtr(EGL_NO_DISPLAY, load, opened);
    eglGetDisplay = reinterpret_cast<PFNEGLGETDISPLAYPROC>(dlsym(opened, "eglGetDisplay"));
    if (!version || !eglGetPlatformDisplay || !eglInitialize || !eglCreateContext || !eglMakeCurrent ||
        !eglGetProcAddress) {
        dlclose(opened);
        throw std::runtime_error("EGL: " + name + " is not an EGL 1.5 library (eglGetPlatformDisplay and friends)");
    }
    lib = opened;
}

std::string egl_error_string(EGLint e) {
    switch (e) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        default: return "EGL error " + std::to_string(e);
    }
}

// EGL displays are initialised once per process and not reference counted: terminate only with the last user.
std::map<EGLDisplay, int>& display_users() {
    static std::map<EGLDisplay, int> users;
    return users;
}
void acquire_display(EGLDisplay d) { ++display_users()[d]; }
void release_display(EGLDisplay d) {
    auto it = display_users().find(d);
    if (it != display_users().end() && --it->second == 0) {
        display_users().erase(it);
        eglTerminate(d);
    }
}

struct EglContext final : GpuContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;

    ~EglContext() override {
        if (context == EGL_NO_CONTEXT) return;
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        release_display(display);
    }
    void make_native_current() override {
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
            throw std::runtime_error("eglMakeCurrent failed: " + egl_error_string(eglGetError()));
    }
    int load_gl_functions() override { return gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)); }
};

// Tries one EGL display: initialise, choose a config, create a 4.5 core context and make it current surfaceless.
bool try_egl_display(EglContext& impl, EGLDisplay display, bool debug, std::string& why) {
    if (display == EGL_NO_DISPLAY) {
        why = "no display (" + egl_error_string(eglGetError()) + ")";
        return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize: " + egl_error_string(eglGetError());
        return false;
    }
    acquire_display(display);
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    auto fail = [&](const std::string& w) {
        why = w;
        release_display(display);
        return false;
    };
    if (!has_extension(ext, "EGL_KHR_surfaceless_context")) return fail("no EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(EGL_OPENGL_API): " + egl_error_string(eglGetError()));
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count == 0) {
        if (!has_extension(ext, "EGL_KHR_no_config_context")) return fail("no EGL config with OpenGL");
        config = nullptr;   // EGL_NO_CONFIG_KHR
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                      EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                                      EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) return fail("eglCreateContext(4.5 core): " + egl_error_string(eglGetError()));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        const EGLint e = eglGetError();
        eglDestroyContext(display, context);
        return fail("eglMakeCurrent(surfaceless): " + egl_error_string(e));
    }
    impl.display = display;
    impl.context = context;
    return true;
}

}  // namespace

std::unique_ptr<GpuContext::Impl> create_egl_context(bool debug) {
    // Mesa's EGL prints its own warnings ("libEGL warning: egl: failed to create dri2 screen") before failing; the
    // failure is reported in our one error line, so keep Mesa to fatal messages unless the user set a level.
    setenv("EGL_LOG_LEVEL", "fatal", /*overwrite=*/0);
    load_egl();
    auto impl = std::make_unique<EglContext>();
    std::string log;
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);   // client extensions (EGL_EXT_client_extensions)
    // 1. A hardware device through EGL_EXT_device_enumeration + EGL_EXT_platform_device (e.g. the NVIDIA GPU).
    if (has_extension(client, "EGL_EXT_platform_device") &&
        (has_extension(client, "EGL_EXT_device_enumeration") || has_extension(client, "EGL_EXT_device_base"))) {
        auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto query_device_string =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (query_devices && query_device_string && query_devices(16, devices, &count)) {
            for (EGLint i = 0; i < count; ++i) {
                const char* dev_ext = query_device_string(devices[i], EGL_EXTENSIONS);
                if (has_extension(dev_ext, "EGL_MESA_device_software")) {
                    log += "egl device " + std::to_string(i) + ": software, skipped; ";
                    continue;
                }
                std::string why;
                EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (try_egl_display(*impl, display, debug, why)) {
                    impl->backend = "egl-device";
                    impl->fallback_log = log;
                    return impl;
                }
                log += "egl device " + std::to_string(i) + ": " + why + "; ";
            }
        } else {
            log += "egl device enumeration failed; ";
        }
    } else {
        log += "no EGL_EXT_platform_device; ";
    }
    // 2. Mesa's surfaceless platform (llvmpipe when there is no GPU).
    if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
        std::string why;
        EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (try_egl_display(*impl, display, debug, why)) {
            impl->backend = "egl-surfaceless";
            impl->fallback_log = log;
            return impl;
        }
        log += "egl surfaceless: " + why + "; ";
    } else {
        log += "no EGL_MESA_platform_surfaceless; ";
    }
    while (!log.empty() && (log.back() == ' ' || log.back() == ';')) log.pop_back();
    throw std::runtime_error("EGL: " + log);
}

}  // namespace rt::gpu
