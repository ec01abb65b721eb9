// GL errors as exceptions. Every GPU pass ends with check_gl("what the pass was"): a GL error then stops the frame
// with a message instead of producing a silent black image. In debug builds (RT_GL_DEBUG) the context also has
// GL_KHR_debug output on (synchronous), and its error messages are added to the exception text.
#pragma once

#include <stdexcept>
#include <string>

#include <glad/gl.h>

namespace rt::gpu {

class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws GlError("<where>: GL_INVALID_OPERATION (...)") when glGetError reports errors (all pending ones are drained
// and named). Cheap: call it after each pass.
void check_gl(const char* where);
inline void check_gl(const std::string& where) { check_gl(where.c_str()); }

// Name of a GL error enum ("GL_INVALID_VALUE", ...).
const char* gl_error_name(GLenum error);

// Installs the GL_KHR_debug callback (synchronous). Messages of high and medium severity go to stderr; errors are
// also kept and appended to the next check_gl exception. Called by create_context when GpuOptions::debug is set.
void enable_gl_debug_output();

}  // namespace rt::gpu
