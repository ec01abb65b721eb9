#include "environment_file.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include <sys/stat.h>

#include "common/scene/scene.h"
#include "common/trace/shading.h"
#include "input_error.h"

#ifdef RT_PORTABLE
#include <stb/stb_image.h>
#else
#include <OpenImageIO/imageio.h>
#endif

namespace rt {

namespace {

[[noreturn]] void refuse(const std::string& file, const std::string& problem) {
    throw InputError("--environment " + file + ": " + problem);
}

std::string number(double v) {
    std::ostringstream out;
    out.precision(6);
    out << v;
    return out.str();
}

// The file's extension in lower case (".hdr" for "sky.HDR").
std::string lower_extension(const std::string& file) {
    std::string ext = std::filesystem::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// Only .hdr and .exr: the two float formats equirectangular maps come in (an 8-bit PNG holds no radiance).
void check_extension(const std::string& file) {
    const std::string ext = lower_extension(file);
    if (ext != ".hdr" && ext != ".exr") refuse(file, "not a .hdr or .exr file");
}

// A regular file we can reach (a FIFO would block the reader, a folder is no image).
void check_regular_file(const std::string& file) {
    struct stat st {};
    if (::stat(file.c_str(), &st) != 0) {
        const int error = errno;
        if (error == ENOENT) refuse(file, "file not found");
        refuse(file, std::system_category().message(error));
    }
    if (S_ISDIR(st.st_mode)) refuse(file, "is a folder, not an image");
    if (!S_ISREG(st.st_mode)) refuse(file, "is not a regular file (a FIFO, socket or device)");
}

void check_size(const std::string& file, long long width, long long height) {
    if (width <= 0 || height <= 0)
        refuse(file, "has no texels (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    if (width > kMaxEnvironmentSide || height > kMaxEnvironmentSide)
        refuse(file, std::to_string(width) + "x" + std::to_string(height) + " is too large: at most " +
                         std::to_string(kMaxEnvironmentSide) + " texels a side");
    if (std::size_t(width) * std::size_t(height) > kMaxEnvironmentTexels)
        refuse(file, std::to_string(width) + "x" + std::to_string(height) + " is too large: at most " +
                         std::to_string(kMaxEnvironmentTexels) + " texels (256 MiB as RGBA float)");
}

#ifdef RT_PORTABLE
// The texels stb_image decodes from bytes (refused, with stb's reason, when it cannot decode them).
// stb_image takes an int length: a longer buffer is read as its first INT32_MAX bytes.
int stb_length(const std::vector<unsigned char>& bytes) {
    return bytes.size() > std::size_t(INT32_MAX) ? INT32_MAX : int(bytes.size());
}

std::vector<float> stb_texels(const std::string& file, const std::vector<unsigned char>& bytes, int& width,
                              int& height, int& channels) {
    float* texels = stbi_loadf_from_memory(bytes.data(), stb_length(bytes), &width, &height, &channels, 0);
    if (!texels) refuse(file, std::string("cannot read its texels: ") + stbi_failure_reason());
    std::vector<float> values(texels, texels + std::size_t(width) * std::size_t(height) * std::size_t(channels));
    stbi_image_free(texels);
    return values;
}
#else
std::string first_line(std::string text) {
    const std::size_t end = text.find('\n');
    if (end != std::string::npos) text.resize(end);
    return text.empty() ? "unknown error" : text;
}
#endif

}  // namespace

Environment make_environment(const std::string& file, int width, int height, int channels,
                             const std::vector<float>& values, float rotation_degrees, float intensity) {
    check_size(file, width, height);
    if (channels != 1 && channels < 3)
        refuse(file, "has " + std::to_string(channels) + " channels: need 1 (grey) or 3 or more (RGB)");
    const std::size_t texels = std::size_t(width) * std::size_t(height);
    if (values.size() < texels * std::size_t(channels)) refuse(file, "has fewer values than its size says");
    if (!std::isfinite(intensity) || intensity < 0.0f || intensity > kMaxEnvironmentIntensity)
        refuse(file, "intensity " + number(intensity) + " is not in [0, 1e20]");
    if (!std::isfinite(rotation_degrees)) refuse(file, "rotation " + number(rotation_degrees) + " is not finite");
    Environment e;
    e.file = file;
    e.width = width;
    e.height = height;
    e.intensity = intensity;
    e.rotation_degrees = rotation_degrees;
    const float radians = rotation_degrees * (kPi / 180.0f);
    e.rotation = {std::cos(radians), std::sin(radians)};
    e.texels.resize(texels);
    for (std::size_t i = 0; i < texels; ++i) {
        const float* t = &values[i * std::size_t(channels)];
        glm::vec4 c(1.0f);
        for (int k = 0; k < 3; ++k) {
            const float v = t[channels == 1 ? 0 : k];
            const char* why = std::isnan(v) ? "NaN" : std::isinf(v) ? "infinite" : v < 0.0f ? "negative" : nullptr;
            // Beyond kMaxRadiance, in the file or once scaled (in double: the product may overflow a float).
            if (!why && (v > kMaxRadiance || double(v) * double(intensity) > double(kMaxRadiance)))
                why = "above 1e20 (kMaxRadiance)";
            if (why)
                refuse(file, "texel (" + std::to_string(i % std::size_t(width)) + ", " +
                                 std::to_string(i / std::size_t(width)) + ") channel " + std::to_string(k) + " is " +
                                 number(v) + (intensity != 1.0f ? " (times intensity " + number(intensity) + ")" : "") +
                                 ": " + why + "; radiance must be finite, >= 0 and <= 1e20");
            c[k] = std::min(v * intensity, kMaxRadiance);   // the float product may round an ulp above
        }
        e.texels[i] = c;
    }
    return e;
}

std::shared_ptr<const Environment> load_environment(const std::string& file, float rotation_degrees, float intensity) {
    check_extension(file);
    check_regular_file(file);
#ifdef RT_PORTABLE
    // Radiance .hdr through stb_image (Debian's libstb, which the portable build carries anyway). Its RGBE decoding
    // is Ward's, as OpenImageIO's is, so the texels are the same floats (portable.* renders the environment golden).
    if (lower_extension(file) == ".exr")
        refuse(file, "this portable build reads no .exr (it has no OpenImageIO): use a .hdr");
    // The largest file a map within kMaxEnvironmentTexels can be (flat RGBE, 4 bytes a texel, and a header): a larger
    // one is refused before it is read into memory.
    const std::uintmax_t largest = std::uintmax_t(kMaxEnvironmentTexels) * 4 + (1u << 20);
    std::error_code size_error;
    if (const std::uintmax_t bytes_on_disk = std::filesystem::file_size(file, size_error);
        !size_error && bytes_on_disk > largest)
        refuse(file, "is " + std::to_string(bytes_on_disk) + " bytes: larger than any .hdr of at most " +
                         std::to_string(kMaxEnvironmentTexels) + " texels");
    std::ifstream in(file, std::ios::binary);
    if (!in) refuse(file, "cannot be opened: " + std::string(std::strerror(errno)));
    std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) refuse(file, "cannot be read");
    if (!stbi_is_hdr_from_memory(bytes.data(), stb_length(bytes))) refuse(file, "is not a Radiance HDR image");
    int width = 0, height = 0, channels = 0;
    // The size first, so that nothing absurd is allocated.
    if (!stbi_info_from_memory(bytes.data(), stb_length(bytes), &width, &height, &channels))
        refuse(file, std::string("not a readable image: ") + stbi_failure_reason());
    check_size(file, width, height);
    // stb reads zeros past the end of a truncated file instead of failing, and a zero run length never ends its
    // scanline (a hang). So decode it twice, followed by 0xFF bytes, then by 0xFE bytes, enough of them to finish
    // the image even as flat RGBE (4 a texel): neither run ever stops, a complete file never reads past its end and
    // decodes the same both times, and a truncated one reads different run lengths, mantissas or exponents.
    const std::size_t original = bytes.size(), padding = std::size_t(width) * std::size_t(height) * 4 + 65536;
    bytes.resize(original + padding, 0xFF);
    const std::vector<float> values = stb_texels(file, bytes, width, height, channels);
    std::fill(bytes.begin() + std::ptrdiff_t(original), bytes.end(), 0xFE);
    const std::vector<float> padded = stb_texels(file, bytes, width, height, channels);
    if (padded.size() != values.size() ||
        !std::equal(values.begin(), values.end(), padded.begin(),
                    [](float x, float y) { return std::memcmp(&x, &y, sizeof x) == 0; }))
        refuse(file, "is truncated: it ends before its last scanline");
    return std::make_shared<const Environment>(
        make_environment(file, width, height, channels, values, rotation_degrees, intensity));
#else
    auto in = OIIO::ImageInput::open(file);
    if (!in) refuse(file, "not a readable image: " + first_line(OIIO::geterror()));
    // OIIO tries every reader when the one the extension names fails: a PNG renamed .hdr would open as a PNG.
    const std::string format = in->format_name();
    if (format != "hdr" && format != "openexr") refuse(file, "is a " + format + " image, not Radiance HDR or OpenEXR");
    const OIIO::ImageSpec spec = in->spec();
    if (spec.deep) refuse(file, "is a deep image");
    if (spec.depth > 1) refuse(file, "is a volume, not a 2D image");
    check_size(file, spec.width, spec.height);
    const int channels = std::min(spec.nchannels, 3);
    if (spec.nchannels != 1 && spec.nchannels < 3)
        refuse(file, "has " + std::to_string(spec.nchannels) + " channels: need 1 (grey) or 3 or more (RGB)");
    std::vector<float> values(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, values.data()))
        refuse(file, "cannot read its texels: " + first_line(in->geterror()));
    in->close();
    return std::make_shared<const Environment>(
        make_environment(file, spec.width, spec.height, channels, values, rotation_degrees, intensity));
#endif
}

}  // namespace rt
