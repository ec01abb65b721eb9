// For the tests that pin what a GPU stage's frame asks of the GPU (gpu_stage.h's gl_dispatches, read_backs and
// upload_bytes in the stats), as one comparable value.
#pragma once

#include <array>
#include <cstdint>
#include <ostream>

#include "common/app/renderer.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "gpu_test_context.h"
#include "pipeline_fixture.h"

namespace rt::gpu {

struct FrameCounts {
    std::uint64_t dispatches = 0, mid_frame_reads = 0, frame_end_reads = 0, scene_bytes = 0, other_bytes = 0;
    bool operator==(const FrameCounts&) const = default;
};

inline FrameCounts frame_counts(const FrameResult& r) {
    return {r.extra.at("gl_dispatches").get<std::uint64_t>(), r.extra.at("read_backs").at("mid_frame").get<std::uint64_t>(),
            r.extra.at("read_backs").at("frame_end").get<std::uint64_t>(),
            r.extra.at("upload_bytes").at("scene").get<std::uint64_t>(),
            r.extra.at("upload_bytes").at("other").get<std::uint64_t>()};
}

inline std::ostream& operator<<(std::ostream& out, const FrameCounts& c) {
    return out << "{" << c.dispatches << " dispatches, " << c.mid_frame_reads << " mid-frame and " << c.frame_end_reads
               << " frame-end read-backs, " << c.scene_bytes << " scene and " << c.other_bytes << " other bytes}";
}

// Two frames of builtin:whitted at 160 x 120 (scripts/bench's size) through `stage`, the scene marked still as the
// driver marks it: the first frame uploads the scene, the second finds it resident.
inline std::array<FrameCounts, 2> whitted_frame_counts(Renderer& stage) {
    test_context();
    FlattenOptions options;
    options.aspect = 160.0f / 120.0f;
    Scene scene = flatten(make_builtin_scene("whitted"), options);
    scene.still_id = 1;
    const RenderSettings settings = fixture_settings(scene, 160, 120);
    const FrameCounts first = frame_counts(stage.render(scene, settings));
    return {first, frame_counts(stage.render(scene, settings))};
}

}  // namespace rt::gpu
