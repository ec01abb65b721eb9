// The window backend (--window): a GLFW window with a GL 4.5 core context. Not built in RT_PORTABLE builds.
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>

#define GLFW_INCLUDE_NONE 1
#include <GLFW/glfw3.h>

#include "context_backend.h"

namespace rt::gpu {

namespace {

// GLFW reports errors through a callback. While the window is being created they are kept and end the one-line
// message of the exception (a failure must read as one line, e.g. "GLFW: glfwInit failed: X11: The DISPLAY
// environment variable is missing"); once it exists they are printed as one-line warnings.
std::string g_glfw_error;
bool g_glfw_created = false;

void glfw_error_callback(int code, const char* text) {
    std::string line = text ? text : "unknown error";
    std::replace(line.begin(), line.end(), '\n', ' ');
    if (g_glfw_created) std::fprintf(stderr, "warning: GLFW error %d: %s\n", code, line.c_str());
    else g_glfw_error = line;
}

std::runtime_error glfw_failure(const std::string& what) {
    return std::runtime_error("GLFW: " + what + (g_glfw_error.empty() ? std::string() : ": " + g_glfw_error));
}

// The viewer's input (context.h, WindowInput) from GLFW's callbacks: drags, wheel and key presses add up between
// two take_input() calls; held movement keys are read when it is called.
char key_char(int key) {
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return char('a' + (key - GLFW_KEY_A));
    if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return char('0' + (key - GLFW_KEY_0));
    if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) return char('0' + (key - GLFW_KEY_KP_0));
    switch (key) {
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: case GLFW_KEY_RIGHT_BRACKET: return '+';
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: case GLFW_KEY_LEFT_BRACKET: return '-';
    case GLFW_KEY_SPACE: return ' ';
    case GLFW_KEY_ESCAPE: return '\x1b';
    default: return 0;
    }
}

struct GlfwContext final : GpuContext::Impl {
    GLFWwindow* window = nullptr;
    WindowInput input;
    bool cursor_known = false;
    double cursor_x = 0, cursor_y = 0;

    static GlfwContext& of(GLFWwindow* w) { return *static_cast<GlfwContext*>(glfwGetWindowUserPointer(w)); }

    void install_callbacks() {
        glfwSetWindowUserPointer(window, this);
        glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
            GlfwContext& self = of(w);
            const glm::vec2 delta(self.cursor_known ? float(x - self.cursor_x) : 0.0f,
                                  self.cursor_known ? float(y - self.cursor_y) : 0.0f);
            self.cursor_known = true;
            self.cursor_x = x;
            self.cursor_y = y;
            const bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
            const bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                               glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
            if ((left && shift) || glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS)
                self.input.pan_drag += delta;
            else if (left)
                self.input.orbit_drag += delta;
        });
        glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) { of(w).input.scroll += float(dy); });
        glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
            if (action != GLFW_PRESS) return;
            if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
            if (const char c = key_char(key)) of(w).input.keys += c;
        });
    }

    float held(int plus, int minus) const {
        return float(glfwGetKey(window, plus) == GLFW_PRESS) - float(glfwGetKey(window, minus) == GLFW_PRESS);
    }

    WindowInput take_input() override {
        WindowInput out = std::exchange(input, WindowInput{});
        out.held = {held(GLFW_KEY_D, GLFW_KEY_A), held(GLFW_KEY_E, GLFW_KEY_Q), held(GLFW_KEY_W, GLFW_KEY_S)};
        int width = 0;
        glfwGetWindowSize(window, &width, &out.window_height);
        return out;
    }

    void wait_events(double seconds) override { glfwWaitEventsTimeout(seconds); }

    void set_title(const std::string& title) override { glfwSetWindowTitle(window, title.c_str()); }

    ~GlfwContext() override {
        if (!window) return;
        glfwDestroyWindow(window);
        glfwTerminate();
        g_glfw_created = false;
    }
    void make_native_current() override { glfwMakeContextCurrent(window); }
    int load_gl_functions() override { return gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress)); }

    bool is_window() const override { return true; }
    bool should_close() const override { return glfwWindowShouldClose(window); }

    bool present(unsigned fbo, int width, int height) override {
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(window, &fw, &fh);
        // Fit the image into the window, keeping its aspect ratio; flip vertically when the stage's rows run
        // top-down is the stage's business (FBO row 0 is the bottom, as GL has it).
        const double s = std::min(double(fw) / width, double(fh) / height);
        const int w = int(width * s), h = int(height * s), x0 = (fw - w) / 2, y0 = (fh - h) / 2;
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glBlitNamedFramebuffer(fbo, 0, 0, 0, width, height, x0, y0, x0 + w, y0 + h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        check_gl("present (blit to window)");
        glfwSwapBuffers(window);
        glfwPollEvents();
        return !glfwWindowShouldClose(window);
    }

    std::vector<std::uint8_t> read_window_rgba8(int& width, int& height) const override {
        glfwGetFramebufferSize(window, &width, &height);
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
    }
};

}  // namespace

std::unique_ptr<GpuContext::Impl> create_glfw_context(const GpuOptions& options) {
    g_glfw_error.clear();
    glfwSetErrorCallback(glfw_error_callback);
    if (!glfwInit()) throw glfw_failure("glfwInit failed (no display?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    auto impl = std::make_unique<GlfwContext>();
    impl->window = glfwCreateWindow(options.window_width, options.window_height, "raytracing course", nullptr, nullptr);
    if (!impl->window) {
        glfwTerminate();
        throw glfw_failure("could not create a window with an OpenGL 4.5 core context");
    }
    g_glfw_created = true;
    glfwMakeContextCurrent(impl->window);
    glfwSwapInterval(0);
    impl->install_callbacks();
    impl->backend = "glfw";
    return impl;
}

}  // namespace rt::gpu
