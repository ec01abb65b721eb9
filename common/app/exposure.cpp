#include "exposure.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace rt {

Exposure parse_exposure(const std::string& text) {
    Exposure e;
    if (text == "auto") {
        e.automatic = true;
        return e;
    }
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || *end != '\0')
        throw std::invalid_argument("'" + text + "' is neither a number nor auto");
    if (!std::isfinite(v)) throw std::invalid_argument(text + " is not a finite number");
    if (std::abs(v) > kMaxExposureEv)
        throw std::invalid_argument(text + " is out of range: must be at least -20 and at most 20");
    e.ev = float(v);
    return e;
}

float auto_exposure_ev(const Image& image) {
    std::vector<float> luminance;
    luminance.reserve(image.pixels.size());
    for (const glm::vec3& p : image.pixels) {
        const float y = 0.2126f * p.r + 0.7152f * p.g + 0.0722f * p.b;
        luminance.push_back(std::isfinite(y) ? std::max(y, 0.0f) : 0.0f);
    }
    if (luminance.empty()) return 0.0f;
    // Nearest rank: the smallest value with at least 99% of the pixels at or below it.
    const std::size_t k = std::size_t(std::ceil(0.99 * double(luminance.size()))) - 1;
    std::nth_element(luminance.begin(), luminance.begin() + std::ptrdiff_t(k), luminance.end());
    const float p99 = luminance[k];
    if (!(p99 > 0.0f)) return 0.0f;
    return std::clamp(-std::log2(p99), -kMaxExposureEv, kMaxExposureEv);
}

float aces_curve(float x) {
    x = std::max(x, 0.0f);
    return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

Image apply_exposure(const Image& image, const Exposure& exposure) {
    if (exposure.is_identity()) return image;
    const float ev = exposure.automatic ? auto_exposure_ev(image) : exposure.ev;
    const float scale = std::exp2(ev);   // exact for integer EV: a power of two only changes the float's exponent
    Image out = image;
    for (glm::vec3& p : out.pixels)
        for (int c = 0; c < 3; ++c) {
            float v = std::min(p[c] * scale, FLT_MAX);
            if (exposure.curve == ToneCurve::Aces) v = aces_curve(v);
            p[c] = v;
        }
    return out;
}

}  // namespace rt
