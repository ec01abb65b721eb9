// The window backend (--window): a GLFW window with a GL 4.5 core context. Not built in RT_PORTABLE builds.
#include <algorithm>
#include <cstdio>
#include <stdexcept>

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

struct GlfwContext final : GpuContext::Impl {
    GLFWwindow* window = nullptr;

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
    impl->backend = "glfw";
    return impl;
}

}  // namespace rt::gpu
