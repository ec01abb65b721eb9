// Window mode of the GPU stages (--window): shows each finished frame in the GLFW window, pixel for pixel, as the
// PNG file would show it (sRGB 8-bit), and saves a screenshot of what the window shows when asked.
//
// The frame goes from the wavefront's image straight to the window's texture on the GPU (present_frame: the
// display pass, common/shaders/viewer/display.comp, applies the exposure and encodes sRGB exactly as the PNG writer
// does); a CPU image (the heatmap, or --exposure auto, which needs the image's percentile) is uploaded instead
// (present).
#pragma once

#include <array>
#include <string>

#include "common/app/exposure.h"
#include "common/app/image.h"
#include "common/gpu/gl/buffer.h"
#include "common/gpu/gl/context.h"
#include "common/gpu/gl/shader.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {

// threshold[k] (k = 1..255): the smallest linear value to_srgb8() encodes as k or more (threshold[0] = 0). The
// display pass encodes v as the largest k with threshold[k] <= v: the same byte as to_srgb8, bit for bit.
std::array<float, 256> srgb8_thresholds();

class WindowPresenter {
public:
    WindowPresenter() = default;
    WindowPresenter(const WindowPresenter&) = delete;
    WindowPresenter& operator=(const WindowPresenter&) = delete;
    ~WindowPresenter();

    // Shows the wavefront's finished frame with `exposure` (not automatic) applied, without a read-back; saves the
    // screenshot (when `screenshot` is not empty) from the back buffer before the swap. False once the user closed
    // the window.
    bool present_frame(GpuContext& context, const Wavefront& wavefront, const Exposure& exposure,
                       const std::string& screenshot);
    // The same for an image on the CPU (uploaded).
    bool present(GpuContext& context, const Image& image, const std::string& screenshot);

private:
    void size_texture(int width, int height);
    bool finish(GpuContext& context, const std::string& screenshot);

    unsigned texture_ = 0, fbo_ = 0;
    int width_ = 0, height_ = 0;
    Program display_;
    Buffer thresholds_;
};

}  // namespace rt::gpu
