// What the stage tests render: a built-in scene flattened for a test image, and the settings of a small test frame.
// One definition for every test binary (compiled into each, like hit_compare.cpp), so a test file holds only its
// cases.
#pragma once

#include <string>
#include <vector>

#include "common/app/renderer.h"
#include "common/scene/scene.h"

namespace rt {

// make_builtin_scene(name) flattened at `time` for an image of the given aspect (width / height).
Scene builtin_scene(const std::string& name, float time = 0.0f, float aspect = 4.0f / 3.0f);
// The same for a width x height image.
Scene builtin_scene_for(const std::string& name, int width, int height);

// A width x height frame of `scene` with the effects it calls for (analyze_effects), recording every ray's hit
// (--dump-hits) and, when asked, the tests per pixel (--heatmap).
RenderSettings test_frame_settings(const Scene& scene, int width = 64, int height = 48,
                                   bool record_tests_per_pixel = false);

// A stage's whole command line (rt::run_stage: options, scene, render, outputs) on `renderer`, as
// `<stage> args...` would run it: its exit status and what it wrote to stderr.
struct StageRun {
    int rc;
    std::string err;
};
StageRun run_stage_command(const std::string& stage, Renderer& renderer, std::vector<std::string> args);
// Bad input's contract: exit 2 and exactly one line, `<stage>: error: ...`, that names `needle`.
void expect_one_line_error(const StageRun& run, const std::string& stage, const std::string& needle);

}  // namespace rt
