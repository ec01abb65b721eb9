// A linear-RGB float image and its files. PNG/JPEG are written as sRGB 8-bit, EXR/HDR as linear float, through
// OpenImageIO (or, in the RT_PORTABLE build for bare GPU machines, PNG only through stb_image_write).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rt {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;   // row-major, row 0 at the top
    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h), glm::vec3(0.0f)) {}
    glm::vec3& at(int x, int y) { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    const glm::vec3& at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// True when the extension is one this build can write (.png .jpg .jpeg .exr .hdr; .png only when portable).
bool is_supported_image_path(const std::string& path);
// The extensions this build writes, for messages: ".png, .jpg, .exr or .hdr" (".png" when portable).
std::string supported_image_types();

// Writes atomically (a temporary file in the same folder, then rename): a failure leaves no half-written file.
// Throws std::runtime_error with a one-line message.
void write_image(const std::string& path, const Image& image);

// Writes `image` into `file` itself, in the format its extension names, for callers that manage their own
// temporaries (the driver). Throws std::runtime_error with the image library's one-line reason.
void write_image_file(const std::string& file, const Image& image);

// Reads any image OpenImageIO can read into linear RGB (8-bit files are taken as sRGB). Not in the portable build.
Image read_image(const std::string& path);

// sRGB-encoded 8-bit values, rounded to nearest (what PNG/JPEG files and windows show); NaN/Inf become 0.
// channels = 3 (RGB) or 4 (RGBA, alpha 255).
std::vector<std::uint8_t> to_srgb8(const Image& image, int channels = 3);

// Number of pixels with a NaN or Inf component.
std::size_t count_non_finite(const Image& image);

}  // namespace rt
