#include "window_presenter.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include <glad/gl.h>

#include "common/trace/shading.h"
#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/gl_check.h"

namespace rt::gpu {

namespace {

int srgb8_code(float v) {
    Image one(1, 1);
    one.pixels[0] = glm::vec3(v);
    return to_srgb8(one)[0];
}

}  // namespace

std::array<float, 256> srgb8_thresholds() {
    // Binary search over the bit patterns of the non-negative floats up to 1 (they sort as their integers); the code
    // grows with v (to_srgb8 is monotone) and is 0 below 0 and 255 from 1 on.
    std::array<float, 256> threshold{};
    const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
    for (int k = 1; k < 256; ++k) {
        std::uint32_t lo = 0, hi = one;   // code(hi) >= k
        while (lo < hi) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            if (srgb8_code(std::bit_cast<float>(mid)) >= k) hi = mid;
            else lo = mid + 1;
        }
        threshold[std::size_t(k)] = std::bit_cast<float>(lo);
    }
    return threshold;
}

WindowPresenter::~WindowPresenter() {
    if (!glDeleteTextures) return;   // no context was ever made
    glDeleteTextures(1, &texture_);
    glDeleteFramebuffers(1, &fbo_);
}

void WindowPresenter::size_texture(int w, int h) {
    if (w == width_ && h == height_) return;
    glDeleteTextures(1, &texture_);
    if (!fbo_) glCreateFramebuffers(1, &fbo_);
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA8, w, h);
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, texture_, 0);
    width_ = w;
    height_ = h;
}

bool WindowPresenter::present_frame(GpuContext& context, const Wavefront& wavefront, const Exposure& exposure,
                                    const std::string& screenshot) {
    size_texture(wavefront.width(), wavefront.height());
    if (!display_) {
        display_ = Program::compute("common/shaders/viewer/display.comp");
        const std::array<float, 256> t = srgb8_thresholds();
        thresholds_.assign(std::vector<float>(t.begin(), t.end()));
    }
    display_.set("display_width", unsigned(width_));
    display_.set("display_height", unsigned(height_));
    display_.set("display_samples", float(std::max(wavefront.samples(), 1)));
    display_.set("display_expose", int(!exposure.is_identity()));
    display_.set("display_scale", std::exp2(exposure.ev));
    display_.set("display_aces", int(exposure.curve == ToneCurve::Aces));
    thresholds_.bind(kBindingScanOut);
    glBindImageTexture(0, texture_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    for (const Wavefront::ImageBand& band : wavefront.image_bands()) {
        band.sums.bind(kBindingScanIn);
        display_.set("display_first", unsigned(band.first));
        display_.set("display_count", unsigned(band.count));
        display_.dispatch_threads(band.count);
    }
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    check_gl("window display pass");
    return finish(context, screenshot);
}

bool WindowPresenter::present(GpuContext& context, const Image& image, const std::string& screenshot) {
    const int w = image.width, h = image.height;
    size_texture(w, h);
    // GL rows run bottom-up: flip while uploading by uploading rows in reverse order.
    const std::vector<std::uint8_t> bytes = to_srgb8(image, 4);
    const std::size_t row = std::size_t(w) * 4;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int y = 0; y < h; ++y)
        glTextureSubImage2D(texture_, 0, 0, h - 1 - y, w, 1, GL_RGBA, GL_UNSIGNED_BYTE, &bytes[std::size_t(y) * row]);
    check_gl("window upload");
    return finish(context, screenshot);
}

bool WindowPresenter::finish(GpuContext& context, const std::string& screenshot) {
    const int w = width_, h = height_;
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
