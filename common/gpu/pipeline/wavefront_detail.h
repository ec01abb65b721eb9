// What the three files of the Wavefront share (wavefront.cpp: the scheduler of passes; wavefront_storage.cpp: batch
// sizes from the storage limit, image bands and compaction; wavefront_records.cpp: --dump-hits, --pixel and the
// frame's diagnostics). Internal to common/gpu: not a header a stage includes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "common/gpu/gl/gl_check.h"
#include "common/gpu/gl/shader.h"

namespace rt::gpu::wavefront_detail {

constexpr std::size_t kTilePixels = 64;                  // 8x8 tiles (wavefront.glsl: wf_tile_pixel)
constexpr std::size_t kRadianceBytesPerPixel = 9 * 4;    // 3 channels x 3 limbs (wf_accumulate)
constexpr std::uint32_t kNoPixel = 0xffffffffu;

// Between passes: shader writes become visible to the next pass, to read-backs and to buffer clears.
inline void pass_barrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT); }

// Times a pass on the stage's GpuTimer, when it gave one, until end() or the end of the scope.
struct PassTimer {
    std::optional<GpuTimer::Scope> scope;
    PassTimer(GpuTimer* timer, const char* phase) {
        if (timer) scope.emplace(*timer, phase);
    }
    void end() { scope.reset(); }
};

}  // namespace rt::gpu::wavefront_detail
