// GL 4.5 core contexts for the GPU stages: headless through EGL (a hardware device when there is one, else Mesa's
// surfaceless platform, i.e. llvmpipe), headless through OSMesa (dlopen'ed only when chosen), or a GLFW window.
// GL functions come through the glad loader (generated at build time) fed by the backend's GetProcAddress; no
// libGL/libOpenGL/libOSMesa is linked. Headless contexts have no default framebuffer: render into FBOs/SSBOs.
// One file per backend: context_egl.cpp, context_osmesa.cpp, context_glfw.cpp (context_backend.h is their interface).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl_check.h"

namespace CLI { class App; }

namespace rt::gpu {

struct GpuOptions {
    std::string backend = "auto";   // auto | egl | osmesa   (auto: EGL, then OSMesa)
    bool window = false;            // GLFW window instead of a headless context (not in RT_PORTABLE builds)
    std::string screenshot;         // window mode: where the stage saves what the window shows (empty = none)
    int window_width = 1024, window_height = 768;
    int moving_scale = 0;           // window mode: frames while the camera moves render at 1/N per axis (0: auto)
#ifdef RT_GL_DEBUG
    bool debug = true;              // GL_KHR_debug output and a debug context
#else
    bool debug = false;
#endif
};

// Adds --backend auto|egl|osmesa, --window, --screenshot FILE, --moving-scale auto|N, --gl-debug to a stage's
// command line.
void add_gpu_options(CLI::App& app, GpuOptions& options);

// Window mode: what the user did with mouse and keyboard since the last take_input() (the viewer's input,
// common/gpu/viewer/viewer.h; GLFW's own codes stay in context_glfw.cpp).
struct WindowInput {
    glm::vec2 orbit_drag{0.0f};   // cursor movement in window pixels with the left button held
    glm::vec2 pan_drag{0.0f};     // ... with the right or middle button held, or shift + left
    float scroll = 0.0f;          // wheel steps, positive = away from the user
    std::string keys;             // keys pressed, in order: 'a'-'z', '0'-'9', '+', '-', ' ' (space), '\x1b' (Esc)
    glm::vec3 held{0.0f};         // movement keys held now: x = D - A, y = E - Q, z = W - S
    int window_height = 0;        // in the units of the drags

    bool moves_camera() const {
        return orbit_drag != glm::vec2(0.0f) || pan_drag != glm::vec2(0.0f) || scroll != 0.0f || held != glm::vec3(0.0f);
    }
    bool empty() const { return !moves_camera() && keys.empty(); }
};

// A current GL 4.5 core context. Move-only; destroying it releases the context (and the window).
// One context is current at a time on the creating thread; make_current() reloads the GL function pointers when
// another context was used in between.
class GpuContext {
public:
    GpuContext();
    GpuContext(GpuContext&&) noexcept;
    GpuContext& operator=(GpuContext&&) noexcept;
    ~GpuContext();

    bool valid() const { return impl_ != nullptr; }
    // "egl-device", "egl-surfaceless", "osmesa" or "glfw".
    const std::string& backend() const;
    // GL_RENDERER, GL_VENDOR and GL_VERSION strings, and the version numbers.
    const std::string& renderer() const;
    const std::string& vendor() const;
    const std::string& version() const;
    int gl_major() const;
    int gl_minor() const;
    // What was tried before this backend succeeded (empty when the first choice worked), for diagnostics.
    const std::string& fallback_log() const;

    void make_current();

    // Window mode only (throws otherwise): shows the colour attachment 0 of `fbo` (w x h) in the window (blit,
    // scaled to fit), swaps and polls events. Returns false once the user closed the window.
    bool present(unsigned fbo, int width, int height);
    bool is_window() const;
    bool should_close() const;
    // Window mode: the window's pixels as RGBA8, rows top to bottom (for --screenshot).
    std::vector<std::uint8_t> read_window_rgba8(int& width, int& height) const;
    // Window mode: the input since the last call (present() polls the events), and the window's title.
    WindowInput take_input();
    // Window mode: sleeps until an input event arrives or `seconds` pass (the viewer idles while nothing changes).
    void wait_events(double seconds);
    void set_title(const std::string& title);

    struct Impl;
private:
    explicit GpuContext(std::unique_ptr<Impl> impl);
    friend GpuContext create_context(const GpuOptions& options);
    std::unique_ptr<Impl> impl_;
};

// Creates and makes current a context as the options ask. Throws std::runtime_error naming every backend tried and
// why it failed.
GpuContext create_context(const GpuOptions& options);

// Headless shortcut: backend "auto", "egl" or "osmesa".
GpuContext create_headless_context(const std::string& backend = "auto", bool debug = false);

}  // namespace rt::gpu
