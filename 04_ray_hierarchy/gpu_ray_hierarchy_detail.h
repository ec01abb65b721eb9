// Stage 04's GPU hierarchy, shared by its two source files (gpu_ray_hierarchy.cpp: groups, build, stats;
// gpu_ray_traversal.cpp: the pair traversal, the leaves and the fold): the limits and the shaders' buffer layouts
// (rh_info.glsl, rh_tally.comp) as the C++ side reads them. Not for use outside the stage.
#pragma once

#include <cstddef>
#include <cstdint>

#include "common/gpu/gl/gl_check.h"

namespace rt::rh_detail {

inline constexpr std::size_t kMaxCapacity = std::size_t(1) << 20;   // entries per buffer: 16 MiB of (node, triangle)
                                                                   // pairs
inline constexpr std::uint32_t kTriangleFlag = 0x80000000u;          // rh_common.glsl: RH_TRIANGLE_FLAG
inline constexpr std::uint32_t kMaxRayIndex = 1u << 27;              // RH_RAY_INDEX_BITS
inline constexpr int kMaxRayLevels = 32;                             // rh_cull.comp's level tables
// rh_info.glsl
inline constexpr std::uint32_t kInfoWords = 224, kInfoExact = 10, kInfoObjectIn = 12, kInfoObjectOut = 14,
                               kInfoLevelIn = 16, kInfoLevelOut = 80, kInfoLeafPairs = 144, kInfoBoxTests = 146,
                               kInfoStepCount = 160,
                               kInfoGroupFirst = 8;
inline constexpr int kMaxSteps = 63;   // rh_info.glsl: RH_INFO_STEP_COUNT slots
// ot_build.comp's ot_levels: levels of the object tree (each at least halves the one below: 2^40 triangles).
inline constexpr std::size_t kMaxObjectLevels = 40;
// rh_tally.comp: per ray kind, the 64-bit sums of rh_info's words kInfoExact .. kInfoBoxTests + 1, then the sphere
// tests and the fold tests.
inline constexpr std::uint32_t kTallyWords = 144, kTallyGroupPairs = 69, kTallySphere = 138, kTallyFold = 140;
// rh_fold.comp: select + step rounds of the closest-hit fold dispatched between two looks at its "more to fold" flag.
inline constexpr int kFoldRoundsPerRead = 2;

// Between passes: storage writes visible to the next pass, to buffer updates and to indirect dispatch arguments.
inline void barrier() {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

// A 64-bit count stored as (lo, hi) uints at w[i], w[i + 1].
inline std::uint64_t word64(const std::uint32_t* w, std::uint32_t i) { return std::uint64_t(w[i + 1]) << 32 | w[i]; }

}  // namespace rt::rh_detail
