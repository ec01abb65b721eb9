// Window mode of the GPU stages (--window): shows each finished frame in the GLFW window, pixel for pixel, as the
// PNG file would show it (sRGB 8-bit), and with --screenshot saves what the window shows.
#pragma once

#include <string>

#include "../app/image.h"
#include "context.h"

namespace rt::gpu {

class WindowPresenter {
public:
    WindowPresenter() = default;
    WindowPresenter(const WindowPresenter&) = delete;
    WindowPresenter& operator=(const WindowPresenter&) = delete;
    ~WindowPresenter();

    // Uploads the image, saves the screenshot (when `screenshot` is not empty) from the back buffer before the
    // swap, then presents. Returns false once the user closed the window.
    bool present(GpuContext& context, const Image& image, const std::string& screenshot);

private:
    unsigned texture_ = 0, fbo_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace rt::gpu
