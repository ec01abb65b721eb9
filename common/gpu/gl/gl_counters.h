// What the CPU asks of the GPU, counted where every such call goes through (Program::dispatch*, Buffer::upload and
// download, GpuTimer::results, texture uploads): the figures a GPU-driven frame keeps small. A GPU stage reads them
// around each part of its frame (gpu_stage.h: gl_dispatches, read_backs, upload_bytes in the stats).
#pragma once

#include <cstdint>

namespace rt::gpu {

struct GlCounters {
    std::uint64_t dispatches = 0;     // compute dispatches, direct or indirect
    std::uint64_t read_backs = 0;     // buffer downloads and timer-query reads: each waits for the GPU
    std::uint64_t upload_bytes = 0;   // bytes sent from the CPU by buffer and texture uploads
};

// This thread's counts since it started (a GL context is current on one thread).
GlCounters& gl_counters();

}  // namespace rt::gpu
