#include "context.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>

#define EGL_NO_X11 1
#define MESA_EGL_NO_X11_HEADERS 1
#include <EGL/egl.h>
#include <EGL/eglext.h>

#ifdef RT_HAVE_GLFW
#define GLFW_INCLUDE_NONE 1
#include <GLFW/glfw3.h>
#endif

#include <CLI/CLI.hpp>

namespace rt::gpu {

// ---------------------------------------------------------------------------------------------------------------
// OSMesa, declared here (osmesa.h would pull in GL/gl.h, which clashes with glad). Values from GL/osmesa.h.
namespace osmesa {
using Context = struct osmesa_context*;
using Proc = void (*)();
constexpr int kFormat = 0x22, kDepthBits = 0x30, kProfile = 0x33, kCoreProfile = 0x34, kMajor = 0x36, kMinor = 0x37;
constexpr unsigned kRgba = 0x1908, kUnsignedByte = 0x1401;
using CreateContextAttribsFn = Context (*)(const int*, Context);
using MakeCurrentFn = unsigned char (*)(Context, void*, unsigned, int, int);
using DestroyContextFn = void (*)(Context);
using GetProcAddressFn = Proc (*)(const char*);
}  // namespace osmesa

namespace {

bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
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

// Which context last filled glad's (global) function pointers.
const void* g_loaded_for = nullptr;

}  // namespace

struct GpuContext::Impl {
    std::string backend, renderer, vendor, version, fallback_log;
    int major = 0, minor = 0;
    // EGL
    EGLDisplay egl_display = EGL_NO_DISPLAY;
    EGLContext egl_context = EGL_NO_CONTEXT;
    // OSMesa
    void* osmesa_lib = nullptr;
    osmesa::Context osmesa_context = nullptr;
    std::vector<std::uint8_t> osmesa_buffer;
    osmesa::MakeCurrentFn osmesa_make_current = nullptr;
    osmesa::DestroyContextFn osmesa_destroy = nullptr;
    osmesa::GetProcAddressFn osmesa_get_proc = nullptr;
#ifdef RT_HAVE_GLFW
    GLFWwindow* window = nullptr;
#endif

    ~Impl() { release(); }

    void release() {
        if (g_loaded_for == this) g_loaded_for = nullptr;
        if (egl_context != EGL_NO_CONTEXT) {
            eglMakeCurrent(egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(egl_display, egl_context);
            egl_context = EGL_NO_CONTEXT;
            release_display(egl_display);
        }
        egl_display = EGL_NO_DISPLAY;
        if (osmesa_context) {
            osmesa_destroy(osmesa_context);
            osmesa_context = nullptr;
        }
        // libOSMesa stays loaded: unloading Mesa (and its LLVM) while anything may still refer to it is not worth it.
#ifdef RT_HAVE_GLFW
        if (window) {
            glfwDestroyWindow(window);
            window = nullptr;
            glfwTerminate();
        }
#endif
    }

    // EGL displays are initialised once per process and not reference counted: terminate only with the last user.
    static std::map<EGLDisplay, int>& display_users() {
        static std::map<EGLDisplay, int> users;
        return users;
    }
    static void acquire_display(EGLDisplay d) { ++display_users()[d]; }
    static void release_display(EGLDisplay d) {
        auto it = display_users().find(d);
        if (it != display_users().end() && --it->second == 0) {
            display_users().erase(it);
            eglTerminate(d);
        }
    }

    void load_gl() {
        int ok = 0;
        if (egl_context != EGL_NO_CONTEXT) {
            ok = gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress));
        } else if (osmesa_context) {
            static osmesa::GetProcAddressFn get = nullptr;
            get = osmesa_get_proc;
            ok = gladLoadGL([](const char* name) { return reinterpret_cast<GLADapiproc>(get(name)); });
        }
#ifdef RT_HAVE_GLFW
        else if (window) {
            ok = gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress));
        }
#endif
        if (!ok) throw std::runtime_error(backend + ": could not load the GL 4.5 core functions (glad)");
        g_loaded_for = this;
    }

    void make_current() {
        if (egl_context != EGL_NO_CONTEXT) {
            if (!eglMakeCurrent(egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_context))
                throw std::runtime_error("eglMakeCurrent failed: " + egl_error_string(eglGetError()));
        } else if (osmesa_context) {
            if (!osmesa_make_current(osmesa_context, osmesa_buffer.data(), osmesa::kUnsignedByte, 16, 16))
                throw std::runtime_error("OSMesaMakeCurrent failed");
        }
#ifdef RT_HAVE_GLFW
        else if (window) {
            glfwMakeContextCurrent(window);
        }
#endif
        if (g_loaded_for != this) load_gl();
    }

    void finish_setup(bool debug) {
        load_gl();
        auto str = [](GLenum e) {
            const GLubyte* s = glGetString(e);
            return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
        };
        renderer = str(GL_RENDERER);
        vendor = str(GL_VENDOR);
        version = str(GL_VERSION);
        glGetIntegerv(GL_MAJOR_VERSION, &major);
        glGetIntegerv(GL_MINOR_VERSION, &minor);
        if (major * 10 + minor < 45)
            throw std::runtime_error(backend + ": got OpenGL " + version + " (" + renderer + "); 4.5 core is required");
        if (debug) enable_gl_debug_output();
        while (glGetError() != GL_NO_ERROR) {}
    }
};

namespace {

// Tries one EGL display: initialise, choose a config, create a 4.5 core context and make it current surfaceless.
bool try_egl_display(GpuContext::Impl& impl, EGLDisplay display, bool debug, std::string& why) {
    if (display == EGL_NO_DISPLAY) {
        why = "no display (" + egl_error_string(eglGetError()) + ")";
        return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize: " + egl_error_string(eglGetError());
        return false;
    }
    GpuContext::Impl::acquire_display(display);
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    auto fail = [&](const std::string& w) {
        why = w;
        GpuContext::Impl::release_display(display);
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
    impl.egl_display = display;
    impl.egl_context = context;
    return true;
}

void create_egl(GpuContext::Impl& impl, bool debug) {
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
                if (try_egl_display(impl, display, debug, why)) {
                    impl.backend = "egl-device";
                    impl.fallback_log = log;
                    return;
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
        if (try_egl_display(impl, display, debug, why)) {
            impl.backend = "egl-surfaceless";
            impl.fallback_log = log;
            return;
        }
        log += "egl surfaceless: " + why + "; ";
    } else {
        log += "no EGL_MESA_platform_surfaceless; ";
    }
    throw std::runtime_error("EGL: " + log);
}

void create_osmesa(GpuContext::Impl& impl, bool debug) {
    (void)debug;   // OSMesa has no debug-context attribute; GL_KHR_debug output still works
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) throw std::runtime_error(std::string("OSMesa: dlopen(libOSMesa.so.8): ") + dlerror());
    auto create = reinterpret_cast<osmesa::CreateContextAttribsFn>(dlsym(lib, "OSMesaCreateContextAttribs"));
    impl.osmesa_make_current = reinterpret_cast<osmesa::MakeCurrentFn>(dlsym(lib, "OSMesaMakeCurrent"));
    impl.osmesa_destroy = reinterpret_cast<osmesa::DestroyContextFn>(dlsym(lib, "OSMesaDestroyContext"));
    impl.osmesa_get_proc = reinterpret_cast<osmesa::GetProcAddressFn>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!create || !impl.osmesa_make_current || !impl.osmesa_destroy || !impl.osmesa_get_proc)
        throw std::runtime_error("OSMesa: libOSMesa.so.8 lacks OSMesaCreateContextAttribs and friends");
    impl.osmesa_lib = lib;
    const int attribs[] = {osmesa::kFormat, int(osmesa::kRgba), osmesa::kDepthBits, 24,
                           osmesa::kProfile, osmesa::kCoreProfile, osmesa::kMajor, 4, osmesa::kMinor, 5, 0};
    impl.osmesa_context = create(attribs, nullptr);
    if (!impl.osmesa_context) throw std::runtime_error("OSMesa: OSMesaCreateContextAttribs(4.5 core) failed");
    impl.osmesa_buffer.assign(16 * 16 * 4, 0);
    if (!impl.osmesa_make_current(impl.osmesa_context, impl.osmesa_buffer.data(), osmesa::kUnsignedByte, 16, 16))
        throw std::runtime_error("OSMesa: OSMesaMakeCurrent failed");
    impl.backend = "osmesa";
}

#ifdef RT_HAVE_GLFW
void create_glfw(GpuContext::Impl& impl, const GpuOptions& options) {
    glfwSetErrorCallback([](int code, const char* text) { std::fprintf(stderr, "GLFW error %d: %s\n", code, text); });
    if (!glfwInit()) throw std::runtime_error("GLFW: glfwInit failed (no display?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    impl.window = glfwCreateWindow(options.window_width, options.window_height, "raytracing course", nullptr, nullptr);
    if (!impl.window) {
        glfwTerminate();
        throw std::runtime_error("GLFW: could not create a window with an OpenGL 4.5 core context");
    }
    glfwMakeContextCurrent(impl.window);
    glfwSwapInterval(0);
    impl.backend = "glfw";
}
#endif

}  // namespace

// ---------------------------------------------------------------------------------------------------------------

GpuContext::GpuContext() = default;
GpuContext::GpuContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GpuContext::GpuContext(GpuContext&&) noexcept = default;
GpuContext& GpuContext::operator=(GpuContext&&) noexcept = default;
GpuContext::~GpuContext() = default;

namespace {
const std::string& empty_string() {
    static const std::string s;
    return s;
}
}  // namespace

const std::string& GpuContext::backend() const { return impl_ ? impl_->backend : empty_string(); }
const std::string& GpuContext::renderer() const { return impl_ ? impl_->renderer : empty_string(); }
const std::string& GpuContext::vendor() const { return impl_ ? impl_->vendor : empty_string(); }
const std::string& GpuContext::version() const { return impl_ ? impl_->version : empty_string(); }
const std::string& GpuContext::fallback_log() const { return impl_ ? impl_->fallback_log : empty_string(); }
int GpuContext::gl_major() const { return impl_ ? impl_->major : 0; }
int GpuContext::gl_minor() const { return impl_ ? impl_->minor : 0; }

void GpuContext::make_current() {
    if (!impl_) throw std::logic_error("GpuContext::make_current on an empty context");
    impl_->make_current();
}

bool GpuContext::is_window() const {
#ifdef RT_HAVE_GLFW
    return impl_ && impl_->window;
#else
    return false;
#endif
}

bool GpuContext::should_close() const {
#ifdef RT_HAVE_GLFW
    return impl_ && impl_->window && glfwWindowShouldClose(impl_->window);
#else
    return false;
#endif
}

bool GpuContext::present(unsigned fbo, int width, int height) {
#ifdef RT_HAVE_GLFW
    if (!is_window()) throw std::logic_error("GpuContext::present: not a window context");
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(impl_->window, &fw, &fh);
    // Fit the image into the window, keeping its aspect ratio; flip vertically when the stage's rows run top-down
    // is the stage's business (FBO row 0 is the bottom, as GL has it).
    const double s = std::min(double(fw) / width, double(fh) / height);
    const int w = int(width * s), h = int(height * s), x0 = (fw - w) / 2, y0 = (fh - h) / 2;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBlitNamedFramebuffer(fbo, 0, 0, 0, width, height, x0, y0, x0 + w, y0 + h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    check_gl("present (blit to window)");
    glfwSwapBuffers(impl_->window);
    glfwPollEvents();
    return !glfwWindowShouldClose(impl_->window);
#else
    (void)fbo;
    (void)width;
    (void)height;
    throw std::logic_error("GpuContext::present: this build has no window support (RT_PORTABLE)");
#endif
}

std::vector<std::uint8_t> GpuContext::read_window_rgba8(int& width, int& height) const {
#ifdef RT_HAVE_GLFW
    if (!is_window()) throw std::logic_error("GpuContext::read_window_rgba8: not a window context");
    glfwGetFramebufferSize(impl_->window, &width, &height);
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    check_gl("read window pixels");
    // GL rows run bottom-up.
    const std::size_t row = std::size_t(width) * 4;
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(y * row), pixels.begin() + std::ptrdiff_t((y + 1) * row),
                         pixels.begin() + std::ptrdiff_t((height - 1 - y) * row));
    return pixels;
#else
    (void)width;
    (void)height;
    throw std::logic_error("GpuContext::read_window_rgba8: this build has no window support (RT_PORTABLE)");
#endif
}

GpuContext create_context(const GpuOptions& options) {
    auto impl = std::make_unique<GpuContext::Impl>();
    if (options.window) {
#ifdef RT_HAVE_GLFW
        create_glfw(*impl, options);
#else
        throw std::runtime_error("--window is not available in this build (RT_PORTABLE: no GLFW); "
                                 "use a headless backend (--backend egl|osmesa)");
#endif
    } else if (options.backend == "egl") {
        create_egl(*impl, options.debug);
    } else if (options.backend == "osmesa") {
        create_osmesa(*impl, options.debug);
    } else if (options.backend == "auto") {
        try {
            create_egl(*impl, options.debug);
        } catch (const std::exception& egl_error) {
            impl->release();
            try {
                create_osmesa(*impl, options.debug);
                impl->fallback_log = egl_error.what();
            } catch (const std::exception& osmesa_error) {
                throw std::runtime_error(std::string("no GL 4.5 context: ") + egl_error.what() + " | " +
                                         osmesa_error.what());
            }
        }
    } else {
        throw std::runtime_error("unknown GPU backend '" + options.backend + "' (auto, egl, osmesa)");
    }
    impl->finish_setup(options.debug);
    return GpuContext(std::move(impl));
}

GpuContext create_headless_context(const std::string& backend, bool debug) {
    GpuOptions options;
    options.backend = backend;
    options.debug = debug;
    return create_context(options);
}

void add_gpu_options(CLI::App& app, GpuOptions& options) {
    app.add_option("--backend", options.backend,
                   "GL context: auto (EGL hardware device, else EGL surfaceless, else OSMesa), egl, osmesa")
        ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
        ->capture_default_str();
    auto* window = app.add_flag("--window", options.window, "Show the frames in a GLFW window (not in portable builds)");
    app.add_option("--screenshot", options.screenshot, "Window mode: save what the window shows to FILE")
        ->needs(window);
    app.add_flag("--gl-debug,!--no-gl-debug", options.debug, "GL_KHR_debug output (on by default in debug builds)");
}

}  // namespace rt::gpu
