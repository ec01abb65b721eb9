#include "stage_test_fixture.h"

#include <gtest/gtest.h>

#include "common/app/driver.h"

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"

namespace rt {

Scene builtin_scene(const std::string& name, float time, float aspect) {
    FlattenOptions options;
    options.time = time;
    options.aspect = aspect;
    return flatten(make_builtin_scene(name), options);
}

Scene builtin_scene_for(const std::string& name, int width, int height) {
    return builtin_scene(name, 0.0f, float(width) / float(height));
}

RenderSettings test_frame_settings(const Scene& scene, int width, int height, bool record_tests_per_pixel) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.effects = analyze_effects(scene);
    settings.record_hits = true;
    settings.record_tests_per_pixel = record_tests_per_pixel;
    return settings;
}

StageRun run_stage_command(const std::string& stage, Renderer& renderer, std::vector<std::string> args) {
    args.insert(args.begin(), stage);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    ::testing::internal::CaptureStderr();
    const int rc = run_stage(stage, int(argv.size()), argv.data(), renderer);
    return {rc, ::testing::internal::GetCapturedStderr()};
}

void expect_one_line_error(const StageRun& run, const std::string& stage, const std::string& needle) {
    EXPECT_EQ(run.rc, 2) << run.err;
    EXPECT_EQ(run.err.rfind(stage + ": error: ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "one line: " << run.err;
}

}  // namespace rt
