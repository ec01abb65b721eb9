// --environment FILE against hostile input (environment_file.h): each problem is one InputError line that names the
// file and says what is wrong, thrown before anything is rendered; a good map loads with its intensity and rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <OpenImageIO/imageio.h>
#include <sys/stat.h>

#include "common/scene/scene.h"
#include "environment_file.h"
#include "image.h"
#include "input_error.h"

namespace rt {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
    const fs::path dir = fs::path(RT_TEST_OUTPUT_DIR) / "environment_file_test";
    fs::create_directories(dir);
    return dir;
}

// A 4x2 map, every texel `value` except texel (1, 1), which is `odd`.
std::string write_map(const std::string& name, float value = 0.5f, glm::vec3 odd = glm::vec3(0.25f)) {
    Image image(4, 2);
    for (glm::vec3& p : image.pixels) p = glm::vec3(value);
    image.at(1, 1) = odd;
    const std::string file = (scratch() / name).string();
    write_image_file(file, image);
    return file;
}

std::string write_bytes(const std::string& name, const std::string& bytes) {
    const std::string file = (scratch() / name).string();
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
}

// The one-line message load_environment refuses `file` with ("" when it loads).
std::string refusal(const std::string& file, float rotation = 0.0f, float intensity = 1.0f) {
    try {
        load_environment(file, rotation, intensity);
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_NE(what.find(file), std::string::npos) << "does not name the file: " << what;
        return what;
    }
    return "";
}

TEST(EnvironmentFile, AGoodMapLoadsWithItsIntensityAndRotation) {
    const std::string file = write_map("good.exr", 0.5f, {1.0f, 2.0f, 3.0f});
    const auto e = load_environment(file, 90.0f, 2.0f);
    ASSERT_EQ(e->width, 4);
    ASSERT_EQ(e->height, 2);
    EXPECT_EQ(e->texels[0], glm::vec4(1.0f, 1.0f, 1.0f, 1.0f));           // 0.5 x intensity 2
    EXPECT_EQ(e->texels[1 * 4 + 1], glm::vec4(2.0f, 4.0f, 6.0f, 1.0f));   // row 1 = the second from the top
    EXPECT_NEAR(e->rotation.x, 0.0f, 1e-7f);
    EXPECT_EQ(e->rotation.y, 1.0f);
    // The same from a Radiance HDR (RGBE: 0.5 and 1, 2, 3 are exact in it).
    const auto hdr = load_environment(write_map("good.hdr", 0.5f, {1.0f, 2.0f, 3.0f}), 0.0f, 1.0f);
    EXPECT_EQ(hdr->texels[1 * 4 + 1], glm::vec4(1.0f, 2.0f, 3.0f, 1.0f));
}

TEST(EnvironmentFile, MissingFolderFifoAndWrongExtensionAreRefused) {
    EXPECT_NE(refusal((scratch() / "no_such_map.hdr").string()).find("file not found"), std::string::npos);
    fs::create_directories(scratch() / "folder.hdr");
    EXPECT_NE(refusal((scratch() / "folder.hdr").string()).find("is a folder"), std::string::npos);
    const std::string fifo = (scratch() / "fifo.exr").string();
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_NE(refusal(fifo).find("not a regular file"), std::string::npos);   // and does not block
    EXPECT_NE(refusal(write_map("map.png")).find("not a .hdr or .exr file"), std::string::npos);
}

TEST(EnvironmentFile, NotAnImageOrAnotherFormatUnderTheNameIsRefused) {
    EXPECT_NE(refusal(write_bytes("text.hdr", "not an image at all\n")).find("not a readable image"), std::string::npos);
    EXPECT_NE(refusal(write_bytes("empty.exr", "")).find("not a readable image"), std::string::npos);
    // A PNG renamed .hdr: OpenImageIO would read it as a PNG.
    const std::string png = write_map("really_png.png");
    const std::string renamed = (scratch() / "really_png.hdr").string();
    fs::copy_file(png, renamed, fs::copy_options::overwrite_existing);
    const std::string why = refusal(renamed);
    EXPECT_TRUE(why.find("is a png image") != std::string::npos || why.find("not a readable image") != std::string::npos)
        << why;
    // A Radiance header whose scanlines are missing.
    EXPECT_NE(refusal(write_bytes("truncated.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n\x01\x02")),
              "");
}

TEST(EnvironmentFile, AbsurdSizesAreRefusedBeforeReadingTexels) {
    // The header claims 20000 x 10; nothing follows. Refused on the size, never allocated.
    const std::string why = refusal(write_bytes("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 10 +X 20000\n"));
    EXPECT_NE(why.find("20000x10 is too large: at most 16384 texels a side"), std::string::npos) << why;
    const std::string many = refusal(write_bytes("many.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n"));
    EXPECT_NE(many.find("at most 16777216 texels"), std::string::npos) << many;
    EXPECT_THROW(make_environment("zero.hdr", 0, 4, 3, {}, 0.0f, 1.0f), InputError);
}

TEST(EnvironmentFile, OneChannelIsGreyTwoAreRefusedAlphaIsIgnored) {
    const Environment grey = make_environment("grey.exr", 2, 1, 1, {0.25f, 4.0f}, 0.0f, 1.0f);
    EXPECT_EQ(grey.texels[1], glm::vec4(4.0f, 4.0f, 4.0f, 1.0f));
    try {
        make_environment("two.exr", 2, 1, 2, {0, 0, 0, 0}, 0.0f, 1.0f);
        ADD_FAILURE() << "2 channels accepted";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--environment two.exr: has 2 channels: need 1 (grey) or 3 or more (RGB)");
    }
    const Environment rgba = make_environment("rgba.exr", 1, 1, 4, {1, 2, 3, -7}, 0.0f, 1.0f);
    EXPECT_EQ(rgba.texels[0], glm::vec4(1.0f, 2.0f, 3.0f, 1.0f));
}

// An EXR of 2x1 texels with `channels` float channels, values 1, 2, 3, ... in file order.
std::string write_exr_channels(const std::string& name, int channels) {
    const std::string file = (scratch() / name).string();
    auto out = OIIO::ImageOutput::create(file);
    std::vector<float> values(std::size_t(2 * channels));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float(i + 1);
    const OIIO::ImageSpec spec(2, 1, channels, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(out && out->open(file, spec) && out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close());
    return file;
}

TEST(EnvironmentFile, FilesWithOneTwoAndFourChannels) {
    const auto grey = load_environment(write_exr_channels("grey.exr", 1), 0.0f, 1.0f);
    EXPECT_EQ(grey->texels[1], glm::vec4(2.0f, 2.0f, 2.0f, 1.0f));
    EXPECT_NE(refusal(write_exr_channels("two.exr", 2)).find("has 2 channels: need 1 (grey) or 3 or more (RGB)"),
              std::string::npos);
    const auto rgba = load_environment(write_exr_channels("rgba.exr", 4), 0.0f, 1.0f);
    EXPECT_EQ(rgba->texels[1], glm::vec4(5.0f, 6.0f, 7.0f, 1.0f));   // R, G, B of the second texel; its A (8) ignored
}

TEST(EnvironmentFile, NanInfiniteNegativeAndTooBrightTexelsAreRefusedNotClamped) {
    const float inf = std::numeric_limits<float>::infinity();
    const std::string nan = refusal(write_map("nan.exr", 0.5f, {0.1f, std::nanf(""), 0.1f}));
    EXPECT_NE(nan.find("texel (1, 1) channel 1 is nan: NaN"), std::string::npos) << nan;
    EXPECT_NE(refusal(write_map("inf.exr", 0.5f, {inf, 0, 0})).find("infinite"), std::string::npos);
    EXPECT_NE(refusal(write_map("negative.exr", 0.5f, {0, 0, -0.01f})).find("negative"), std::string::npos);
    EXPECT_NE(refusal(write_map("bright.exr", 0.5f, {2e20f, 0, 0})).find("above 1e20"), std::string::npos);
    // Too bright in the file, even when the intensity would bring it down.
    EXPECT_NE(refusal(write_map("bright_dimmed.exr", 0.5f, {2e20f, 0, 0}), 0.0f, 0.1f).find("above 1e20"),
              std::string::npos);
    // Fine alone, beyond kMaxRadiance once scaled by the intensity (the product is checked in double).
    const std::string scaled = refusal(write_map("scaled.exr", 0.5f, {1e10f, 0, 0}), 0.0f, 1e15f);
    EXPECT_NE(scaled.find("(times intensity 1e+15): above 1e20"), std::string::npos) << scaled;
}

TEST(EnvironmentFile, IntensityOutsideItsRangeAndANonFiniteRotationAreRefused) {
    EXPECT_THROW(make_environment("i.exr", 1, 1, 3, {1, 1, 1}, 0.0f, std::nanf("")), InputError);
    EXPECT_THROW(make_environment("i.exr", 1, 1, 3, {1, 1, 1}, 0.0f, -1.0f), InputError);
    EXPECT_THROW(make_environment("i.exr", 1, 1, 3, {1, 1, 1}, 0.0f, std::numeric_limits<float>::infinity()), InputError);
    EXPECT_EQ(make_environment("i.exr", 1, 1, 3, {1, 1, 1}, 0.0f, 0.0f).texels[0], glm::vec4(0, 0, 0, 1));
    EXPECT_THROW(make_environment("r.exr", 1, 1, 3, {1, 1, 1}, std::nanf(""), 1.0f), InputError);
}

}  // namespace
}  // namespace rt
