#include "gl_check.h"

#include <cstdio>
#include <mutex>

namespace rt::gpu {

namespace {
std::mutex g_debug_mutex;
std::string g_debug_errors;   // GL_DEBUG_TYPE_ERROR messages since the last check_gl

void GLAD_API_PTR debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                 const GLchar* message, const void* /*user*/) {
    (void)source;
    (void)id;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    const std::string text(message, length >= 0 ? std::size_t(length) : std::char_traits<char>::length(message));
    if (type == GL_DEBUG_TYPE_ERROR) {
        std::lock_guard lock(g_debug_mutex);
        if (!g_debug_errors.empty()) g_debug_errors += "; ";
        g_debug_errors += text;
    }
    if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM)
        std::fprintf(stderr, "GL debug: %s\n", text.c_str());
}
}  // namespace

const char* gl_error_name(GLenum error) {
    switch (error) {
        case GL_NO_ERROR: return "GL_NO_ERROR";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
        case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
        default: return "unknown GL error";
    }
}

void check_gl(const char* where) {
    std::string errors;
    for (int i = 0; i < 16; ++i) {   // bounded: a lost context may report errors forever
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        if (!errors.empty()) errors += ", ";
        errors += gl_error_name(e);
        if (e == GL_CONTEXT_LOST) break;
    }
    std::string debug;
    {
        std::lock_guard lock(g_debug_mutex);
        debug.swap(g_debug_errors);
    }
    if (errors.empty()) return;
    std::string message = std::string(where) + ": " + errors;
    if (!debug.empty()) message += " (" + debug + ")";
    throw GlError(message);
}

void enable_gl_debug_output() {
    if (!glDebugMessageCallback) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

}  // namespace rt::gpu
