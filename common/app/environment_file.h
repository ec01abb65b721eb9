// Reading --environment FILE (docs/shading.md, "The environment"): an equirectangular .hdr or .exr, linear RGB,
// checked completely before anything is rendered. Every problem is an InputError of one line naming the file
// (the driver prints it and exits 2): no file, not a regular file, another extension, not an image of that kind,
// a size beyond the limits below, 2 channels, and any texel that is NaN, infinite, negative or above kMaxRadiance
// (refused, never clamped: a broken map should be fixed, not hidden).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/scene/environment_map.h"

namespace rt {

constexpr int kMaxEnvironmentSide = 16384;                          // texels a side (GL_MAX_TEXTURE_SIZE is >= this
                                                                    // on most GPUs; the GPU stages check theirs)
constexpr std::size_t kMaxEnvironmentTexels = std::size_t(1) << 24;  // 256 MiB as RGBA float (8192 x 2048)
constexpr float kMaxEnvironmentIntensity = 1e20f;                   // --environment-intensity's upper bound
constexpr float kMaxEnvironmentRotation = 1e6f;                     // degrees, either way

// Builds the environment from `channels` floats per texel, row 0 on top: 1 channel is grey (copied to R, G and B),
// 3 or more are R, G, B (any further channel, alpha included, is ignored); 2 are refused. `intensity` multiplies
// every texel; the product must stay <= kMaxRadiance.
Environment make_environment(const std::string& file, int width, int height, int channels,
                             const std::vector<float>& values, float rotation_degrees, float intensity);

// Reads and checks `file` (make_environment's rules, plus the file checks above).
std::shared_ptr<const Environment> load_environment(const std::string& file, float rotation_degrees, float intensity);

}  // namespace rt
