// GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes one shader storage block may see (llvmpipe: 128 MiB; NVIDIA:
// 2 GiB and more). A buffer bound past it is undefined behaviour, so the GPU primitives check sizes against it and
// throw a one-line error naming both numbers instead.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

#include "gl_check.h"

namespace rt::gpu {

// Needs a current context.
inline std::size_t max_storage_block_bytes() {
    GLint64 bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
    return std::size_t(bytes);
}

// "134217732 bytes (128.0 MiB)": sizes in messages.
inline std::string describe_bytes(std::size_t bytes) {
    char mib[32];
    std::snprintf(mib, sizeof mib, "%.1f", double(bytes) / (1024.0 * 1024.0));
    return std::to_string(bytes) + " bytes (" + mib + " MiB)";
}

}  // namespace rt::gpu
