// Exposure: how bright the image is shown and saved. A display step, not lighting: the renderer computes radiance as
// the scene's lights give it, and only the pixels written to files (and shown in a window) are scaled, by 2^EV, then
// optionally passed through a tone curve (docs/shading.md, "Exposure"). Stats, hits and heatmaps never see it.
//   --exposure EV      a number in [-20, 20] (0 = unchanged, 1 = twice as bright), or "auto"
//   --tone-curve C     none (default: linear, clipped at 1 by 8-bit files) or aces (a smooth shoulder instead of clipping)
#pragma once

#include <string>

#include "image.h"

namespace rt {

enum class ToneCurve { None, Aces };

constexpr float kMaxExposureEv = 20.0f;   // |EV| at most this: 2^20 is a million, enough for photometric lights

struct Exposure {
    bool automatic = false;            // --exposure auto: auto_exposure_ev() of each frame
    float ev = 0.0f;                   // the EV when not automatic
    ToneCurve curve = ToneCurve::None;
    bool is_identity() const { return !automatic && ev == 0.0f && curve == ToneCurve::None; }
};

// Parses an --exposure value: "auto" or a finite number in [-20, 20]. Throws std::invalid_argument with one line.
Exposure parse_exposure(const std::string& text);

// --exposure auto: the EV that maps the 99th percentile of the image's luminance (Rec. 709 weights) to 1, so at most
// 1% of the pixels clip; 0 for an image with that percentile at 0 (black), clamped to [-20, 20].
float auto_exposure_ev(const Image& image);

// ACES filmic curve, Narkowicz's 2015 fit: (x (2.51 x + 0.03)) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1].
float aces_curve(float x);

// The image as it is saved and shown: every channel times 2^EV, then the tone curve. Returns `image` unchanged
// (bit for bit) for the identity exposure; results stay finite (at most FLT_MAX).
Image apply_exposure(const Image& image, const Exposure& exposure);

}  // namespace rt
