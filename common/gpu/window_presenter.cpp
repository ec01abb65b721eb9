#include "window_presenter.h"

#include <glad/gl.h>

#include "../trace/shading.h"
#include "gl_check.h"

namespace rt::gpu {

WindowPresenter::~WindowPresenter() {
    if (!glDeleteTextures) return;   // no context was ever made
    glDeleteTextures(1, &texture_);
    glDeleteFramebuffers(1, &fbo_);
}

bool WindowPresenter::present(GpuContext& context, const Image& image, const std::string& screenshot) {
    const int w = image.width, h = image.height;
    if (w != width_ || h != height_) {
        glDeleteTextures(1, &texture_);
        if (!fbo_) glCreateFramebuffers(1, &fbo_);
        glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
        glTextureStorage2D(texture_, 1, GL_RGBA8, w, h);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, texture_, 0);
        width_ = w;
        height_ = h;
    }
    // GL rows run bottom-up: flip while uploading by uploading rows in reverse order.
    const std::vector<std::uint8_t> bytes = to_srgb8(image, 4);
    const std::size_t row = std::size_t(w) * 4;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int y = 0; y < h; ++y)
        glTextureSubImage2D(texture_, 0, 0, h - 1 - y, w, 1, GL_RGBA, GL_UNSIGNED_BYTE, &bytes[std::size_t(y) * row]);
    check_gl("window upload");
    if (!screenshot.empty()) {
        // Draw into the back buffer as present() will, and read it before the swap (after it, it is undefined).
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitNamedFramebuffer(fbo_, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        int sw = 0, sh = 0;
        const std::vector<std::uint8_t> shown = context.read_window_rgba8(sw, sh);
        Image shot(sw, sh);
        for (std::size_t i = 0; i < shot.pixels.size(); ++i)
            for (int k = 0; k < 3; ++k) shot.pixels[i][k] = srgb_to_linear(float(shown[i * 4 + std::size_t(k)]) / 255.0f);
        write_image(screenshot, shot);
    }
    return context.present(fbo_, w, h);
}

}  // namespace rt::gpu
