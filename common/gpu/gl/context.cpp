// What the backends share (context_backend.h): choosing one (create_context), loading GL through glad, the checks
// after creation, and the command-line options. The backends are context_egl.cpp, context_osmesa.cpp and
// context_glfw.cpp.
#include "context.h"

#include <dlfcn.h>

#include <stdexcept>

#include <CLI/CLI.hpp>

#include "context_backend.h"

namespace rt::gpu {

namespace {
// Which context last filled glad's (global) function pointers.
const void* g_loaded_for = nullptr;
}  // namespace

GpuContext::Impl::~Impl() {
    if (g_loaded_for == this) g_loaded_for = nullptr;
}

void GpuContext::Impl::load_gl() {
    if (!load_gl_functions()) throw std::runtime_error(backend + ": could not load the GL 4.5 core functions (glad)");
    g_loaded_for = this;
}

void GpuContext::Impl::make_current() {
    make_native_current();
    if (g_loaded_for != this) load_gl();
}

void GpuContext::Impl::finish_setup(bool debug) {
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

void* open_backend_library(const std::string& who, const std::string& name) {
    if (void* lib = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL)) return lib;
    const char* error = dlerror();
    std::string why = error ? error : "dlopen failed";
    if (why.rfind(name + ": ", 0) == 0) why.erase(0, name.size() + 2);   // "NAME: cannot open shared object file"
    throw std::runtime_error(who + ": cannot load " + name + ": " + why);
}

bool GpuContext::Impl::present(unsigned, int, int) {
    throw std::logic_error("GpuContext::present: not a window context");
}

std::vector<std::uint8_t> GpuContext::Impl::read_window_rgba8(int&, int&) const {
    throw std::logic_error("GpuContext::read_window_rgba8: not a window context");
}

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


bool GpuContext::is_window() const { return impl_ && impl_->is_window(); }
bool GpuContext::should_close() const { return impl_ && impl_->should_close(); }

bool GpuContext::present(unsigned fbo, int width, int height) {
    if (!impl_) throw std::logic_error("GpuContext::present: not a window context");
    return impl_->present(fbo, width, height);
}

std::vector<std::uint8_t> GpuContext::read_window_rgba8(int& width, int& height) const {
    if (!impl_) throw std::logic_error("GpuContext::read_window_rgba8: not a window context");
    return impl_->read_window_rgba8(width, height);
}

WindowInput GpuContext::take_input() { return impl_ ? impl_->take_input() : WindowInput{}; }
void GpuContext::wait_events(double seconds) {
    if (impl_) impl_->wait_events(seconds);
}
void GpuContext::set_title(const std::string& title) {
    if (impl_) impl_->set_title(title);
}

GpuContext create_context(const GpuOptions& options) {
    std::unique_ptr<GpuContext::Impl> impl;
    if (options.window) {
#ifdef RT_HAVE_GLFW
        impl = create_glfw_context(options);
#else
        throw std::runtime_error("--window is not available in this build (RT_PORTABLE: no GLFW); "
                                 "use a headless backend (--backend egl|osmesa)");
#endif
    } else if (options.backend == "egl") {
        impl = create_egl_context(options.debug);
    } else if (options.backend == "osmesa") {
        impl = create_osmesa_context(options.debug);
    } else if (options.backend == "auto") {
        try {
            impl = create_egl_context(options.debug);
        } catch (const std::exception& egl_error) {
            try {
                impl = create_osmesa_context(options.debug);
                impl->fallback_log = egl_error.what();
            } catch (const std::exception& osmesa_error) {
                throw std::runtime_error(std::string("no GL 4.5 context: ") + egl_error.what() + "; " +
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
    auto* window = app.add_flag("--window", options.window, "Show the frames in an interactive GLFW viewer window (controls: README.md; not in portable builds)");
    app.add_option("--screenshot", options.screenshot, "Window mode: save what the window shows to FILE")
        ->needs(window);
    app.add_option_function<std::string>(
           "--moving-scale",
           [&options](const std::string& text) { options.moving_scale = text == "auto" ? 0 : std::stoi(text); },
           "Window mode: while the camera moves, render at 1/N of the resolution per axis (auto: N from the frame "
           "times, for about 66 ms per frame; 1: always full resolution)")
        ->check([](const std::string& text) -> std::string {
            if (text == "auto") return {};
            if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 2)
                return "'" + text + "' is not auto or a whole number from 1 to 16";
            const int n = std::stoi(text);
            return n >= 1 && n <= 16 ? std::string() : text + " is out of range: must be auto or 1 to 16";
        })
        ->needs(window)
        ->default_str("auto");
    app.add_flag("--gl-debug,!--no-gl-debug", options.debug, "GL_KHR_debug output (on by default in debug builds)");
}

}  // namespace rt::gpu
