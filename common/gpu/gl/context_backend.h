// Inside GpuContext (context.h): what every backend provides. One file per backend implements it:
// context_egl.cpp (EGL device / surfaceless), context_osmesa.cpp (OSMesa through dlopen), context_glfw.cpp (a GLFW
// window, not in RT_PORTABLE builds). context.cpp chooses the backend and holds what they share.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "context.h"

namespace rt::gpu {

struct GpuContext::Impl {
    std::string backend, renderer, vendor, version, fallback_log;
    int major = 0, minor = 0;

    virtual ~Impl();

    // Makes the backend's context current on this thread, then loads the GL functions when another context filled
    // glad's (global) function pointers since.
    void make_current();
    // After creation (the context is current): loads GL, reads the strings, checks for 4.5, enables debug output.
    void finish_setup(bool debug);

    // Window backends only (the defaults throw std::logic_error: not a window context).
    virtual bool is_window() const { return false; }
    virtual bool should_close() const { return false; }
    virtual bool present(unsigned fbo, int width, int height);
    virtual std::vector<std::uint8_t> read_window_rgba8(int& width, int& height) const;
    virtual WindowInput take_input() { return {}; }
    virtual void wait_events(double /*seconds*/) {}
    virtual void set_title(const std::string& /*title*/) {}

protected:
    virtual void make_native_current() = 0;   // eglMakeCurrent, OSMesaMakeCurrent, glfwMakeContextCurrent
    virtual int load_gl_functions() = 0;      // gladLoadGL with the backend's GetProcAddress; 0 on failure

private:
    void load_gl();
};

// Opens a backend's library (dlopen, RTLD_NOW | RTLD_LOCAL; it stays loaded). When it cannot, throws "WHO: cannot load
// NAME: why" (dlerror's reason without the file name it repeats).
void* open_backend_library(const std::string& who, const std::string& name);

// Each creates a context, makes it current, and sets `backend` (and `fallback_log`); throws std::runtime_error
// saying why it failed, after releasing what it had made.
std::unique_ptr<GpuContext::Impl> create_egl_context(bool debug);
std::unique_ptr<GpuContext::Impl> create_osmesa_context(bool debug);
#ifdef RT_HAVE_GLFW
std::unique_ptr<GpuContext::Impl> create_glfw_context(const GpuOptions& options);
#endif

}  // namespace rt::gpu
