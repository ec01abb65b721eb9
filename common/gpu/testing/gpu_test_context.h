// For the unit tests: one headless context per test process (created on first use, made current on every call).
#pragma once

#include "common/gpu/gl/context.h"

namespace rt::gpu {

inline GpuContext& test_context() {
    static GpuContext context = create_headless_context("auto", true);
    context.make_current();
    return context;
}

}  // namespace rt::gpu
