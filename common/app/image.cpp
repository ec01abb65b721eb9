#include "image.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "common/scene/whole_file.h"
#include "common/trace/shading.h"
#include "atomic_file.h"

#ifdef RT_PORTABLE
#include <stb/stb_image_write.h>
#else
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#endif

namespace rt {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

#ifndef RT_PORTABLE
bool is_float_format(const std::string& ext) { return ext == ".exr" || ext == ".hdr"; }
#endif

}  // namespace

std::vector<std::uint8_t> to_srgb8(const Image& image, int channels) {
    const std::size_t n = std::size_t(channels);
    std::vector<std::uint8_t> bytes(image.pixels.size() * n, 255);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = image.pixels[i][c];
            bytes[i * n + std::size_t(c)] = std::uint8_t(std::lround(linear_to_srgb(std::isfinite(v) ? v : 0.0f) * 255.0f));
        }
    return bytes;
}

bool is_supported_image_path(const std::string& path) {
    const std::string ext = lower_extension(path);
#ifdef RT_PORTABLE
    return ext == ".png";
#else
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".exr" || ext == ".hdr";
#endif
}

std::string supported_image_types() {
#ifdef RT_PORTABLE
    return ".png (portable build)";
#else
    return ".png, .jpg, .exr or .hdr";
#endif
}

void write_image(const std::string& path, const Image& image) {
    if (!is_supported_image_path(path)) throw std::runtime_error("unsupported image type: " + path);
    const std::string tmp = create_temporary(path);
    try {
        write_image_file(tmp, image);
    } catch (const std::runtime_error& e) {
        discard_temporary(tmp);
        throw std::runtime_error("cannot write image " + path + ": " + e.what());
    }
    commit_temporary(tmp, path);
}

// The image is encoded into memory (OpenImageIO's IOVecOutput proxy; stb's callback in the portable build), then
// written by write_whole_file, which checks every write: OpenImageIO's PNG writer does not report a short write, and
// libjpeg's error handler would end the process. So a full disk is one error line, never a truncated
// image.
void write_image_file(const std::string& file, const Image& image) {
    const std::string ext = lower_extension(file);
    bool ok = false;
    std::string error;
    std::vector<unsigned char> encoded;
#ifdef RT_PORTABLE
    const std::vector<std::uint8_t> bytes = to_srgb8(image);
    const auto append = [](void* context, void* data, int size) {
        auto& out = *static_cast<std::vector<unsigned char>*>(context);
        out.insert(out.end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    ok = stbi_write_png_to_func(append, &encoded, image.width, image.height, 3, bytes.data(), image.width * 3) != 0;
    if (!ok) error = "stb_image_write failed";
#else
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create(file);
    if (!out) {
        error = OIIO::geterror();
    } else if (!out->supports("ioproxy") || !out->set_ioproxy(&memory)) {
        error = out->format_name() + std::string(" writer cannot encode into memory");
    } else if (is_float_format(ext)) {
        OIIO::ImageSpec spec(image.width, image.height, 3, ext == ".exr" ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        if (ext == ".exr") spec.format = OIIO::TypeDesc::FLOAT;   // full float: the NaN/Inf checks need exact values
        ok = out->open(file, spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) && out->close();
        if (!ok) error = out->geterror();
    } else {
        const std::vector<std::uint8_t> bytes = to_srgb8(image);
        OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        if (ext == ".jpg" || ext == ".jpeg") spec.attribute("Compression", "jpeg:95");
        ok = out->open(file, spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) && out->close();
        if (!ok) error = out->geterror();
    }
    out.reset();   // flushes into `encoded` before it is written
#endif
    if (ok && encoded.empty()) {
        ok = false;
        error = "the image writer produced no bytes";
    }
    if (!ok) throw std::runtime_error(error.empty() ? std::string("the image library failed") : error);
    write_whole_file(file, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

Image read_image(const std::string& path) {
#ifdef RT_PORTABLE
    throw std::runtime_error("reading images is not available in the portable build: " + path);
#else
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot read image " + path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = spec.nchannels;
    std::vector<float> data(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        throw std::runtime_error("cannot read image " + path + ": " + in->geterror());
    const bool linear_file = spec.format.is_floating_point();
    Image image(spec.width, spec.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = data[i * std::size_t(channels) + std::size_t(std::min(c, channels - 1))];
            image.pixels[i][c] = linear_file ? v : srgb_to_linear(v);
        }
    return image;
#endif
}

std::size_t count_non_finite(const Image& image) {
    return std::size_t(std::count_if(image.pixels.begin(), image.pixels.end(), [](const glm::vec3& p) {
        return !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    }));
}

}  // namespace rt
