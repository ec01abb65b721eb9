// image_compare: the golden-image check. Compares an image a stage rendered with a reference through OpenImageIO's
// ImageBufAlgo::compare, on 8-bit sRGB values in [0, 1] (float images are encoded exactly as the stages write PNG).
//
// A pixel fails when any channel differs by more than --threshold; the comparison fails when more than
// --fail-fraction of the pixels fail (the README states and justifies the defaults). Float inputs must not contain
// NaN or Inf. On failure it prints the metrics and writes actual, reference and an amplified difference into
// --diff-dir. Exit code: 0 pass, 1 fail, 2 bad input.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "common/trace/shading.h"

namespace {

// Loads an image as sRGB-encoded values quantised to 8 bits; counts non-finite pixels of float files.
OIIO::ImageBuf load_as_srgb8(const std::string& path, std::size_t& non_finite) {
    OIIO::ImageBuf in(path);
    if (!in.read(0, 0, true, OIIO::TypeDesc::FLOAT)) throw std::runtime_error("cannot read " + path + ": " + in.geterror());
    const OIIO::ImageSpec& spec = in.spec();
    const bool linear = spec.format.is_floating_point() && (path.ends_with(".exr") || path.ends_with(".hdr"));
    OIIO::ImageSpec out_spec(spec.width, spec.height, 3, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf out(out_spec);
    non_finite = 0;
    std::vector<float> px(std::size_t(spec.nchannels));
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) {
            in.getpixel(x, y, px.data(), spec.nchannels);
            float rgb[3];
            bool finite = true;
            for (int c = 0; c < 3; ++c) {
                float v = px[std::size_t(std::min(c, spec.nchannels - 1))];
                if (!std::isfinite(v)) { finite = false; v = 0.0f; }
                // Encode floats exactly as rt::write_image does for PNG: sRGB, rounded to 8 bits.
                if (linear) v = std::lround(rt::linear_to_srgb(v) * 255.0f) / 255.0f;
                rgb[c] = v;
            }
            if (!finite) ++non_finite;
            out.setpixel(x, y, rgb, 3);
        }
    return out;
}

void save(const OIIO::ImageBuf& image, const std::string& path) {
    OIIO::ImageBuf copy = image;
    copy.set_write_format(OIIO::TypeDesc::UINT8);
    if (!copy.write(path)) std::fprintf(stderr, "image_compare: cannot write %s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Compare a rendered image with a reference (golden-image tests)", "image_compare"};
    std::string actual_path, reference_path, diff_dir, name = "image";
    double threshold = 0.016, fail_fraction = 0.01;
    bool finite_only = false;
    app.add_option("actual", actual_path, "Rendered image (.exr checked for NaN/Inf)")->required();
    app.add_option("reference", reference_path, "Reference image (not with --finite-only)");
    app.add_flag("--finite-only", finite_only, "Only check that every pixel of the actual image is finite");
    app.add_option("--threshold", threshold, "Per-channel difference above which a pixel fails")->capture_default_str();
    app.add_option("--fail-fraction", fail_fraction, "Largest fraction of failing pixels that still passes")->capture_default_str();
    app.add_option("--diff-dir", diff_dir, "Where to write actual/reference/difference images on failure");
    app.add_option("--name", name, "Base name of the files written on failure");
    CLI11_PARSE(app, argc, argv);
    if (finite_only == !reference_path.empty()) {
        std::fprintf(stderr, "image_compare: error: give a reference image or --finite-only, not both\n");
        return 2;
    }

    try {
        std::size_t actual_nan = 0, reference_nan = 0;
        const OIIO::ImageBuf actual = load_as_srgb8(actual_path, actual_nan);
        if (finite_only) {
            std::printf("%s %s: non-finite pixels %zu\n", actual_nan == 0 ? "PASS" : "FAIL", name.c_str(), actual_nan);
            return actual_nan == 0 ? 0 : 1;
        }
        const OIIO::ImageBuf reference = load_as_srgb8(reference_path, reference_nan);
        const auto& a = actual.spec();
        const auto& r = reference.spec();
        if (a.width != r.width || a.height != r.height) {
            std::printf("FAIL %s: size %dx%d differs from the reference's %dx%d\n", name.c_str(), a.width, a.height,
                        r.width, r.height);
            return 1;
        }
        const auto result = OIIO::ImageBufAlgo::compare(actual, reference, float(threshold), float(threshold));
        const double pixels = double(a.width) * double(a.height);
        const double failing = double(result.nfail) / pixels;
        const bool pass = actual_nan == 0 && failing <= fail_fraction;
        std::printf("%s %s: failing pixels %.4f%% (limit %.4f%%, threshold %.4f), mean error %.6f, RMS %.6f, "
                    "PSNR %.2f dB, max error %.4f at (%d,%d), non-finite pixels %zu\n",
                    pass ? "PASS" : "FAIL", name.c_str(), 100.0 * failing, 100.0 * fail_fraction, threshold,
                    result.meanerror, result.rms_error, result.PSNR, result.maxerror, result.maxx, result.maxy,
                    actual_nan);
        if (!pass && !diff_dir.empty()) {
            std::filesystem::create_directories(diff_dir);
            const std::string base = (std::filesystem::path(diff_dir) / name).string();
            save(actual, base + ".actual.png");
            save(reference, base + ".reference.png");
            OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, reference);
            diff = OIIO::ImageBufAlgo::mul(diff, 10.0f);   // amplified so small differences show
            save(diff, base + ".diff.png");
            std::printf("  wrote %s.{actual,reference,diff}.png\n", base.c_str());
        }
        return pass ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_compare: error: %s\n", e.what());
        return 2;
    }
}
