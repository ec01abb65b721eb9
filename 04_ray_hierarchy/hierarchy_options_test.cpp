// Stage 04's own options through the stage's command line (rt::run_stage): a bad --branching, --levels or
// --objects is one line `04_ray_hierarchy: error: ...` and exit 2, before anything is rendered or written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "ray_hierarchy_renderer.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

StageRun run_stage_04(std::vector<std::string> args) {
    RayHierarchyRenderer renderer;
    return run_stage_command("04_ray_hierarchy", renderer, std::move(args));
}

TEST(HierarchyOptions, BadValuesAreOneLineErrorsWithExit2) {
    const std::string out = std::string(RT_TEST_OUTPUT_DIR) + "/hierarchy_options.png";
    std::filesystem::create_directories(RT_TEST_OUTPUT_DIR);
    for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
             {"--branching", "2"}, {"--branching", "5"}, {"--branching", "32"}, {"--branching", "x"},
             {"--levels", "-1"}, {"--levels", "33"}, {"--levels", "nan"}, {"--objects", "yes"}, {"--objects", ""}, {"--objects", "tree,meshes"}}) {
        std::filesystem::remove(out);
        std::vector<std::string> args = {"--scene", "builtin:whitted", "--width", "8", "--height", "6", "--out", out};
        args.insert(args.end(), bad.begin(), bad.end());
        expect_one_line_error(run_stage_04(args), "04_ray_hierarchy", bad[0]);
        EXPECT_FALSE(std::filesystem::exists(out)) << bad[0] << " " << bad[1];
    }
}

TEST(HierarchyOptions, GoodValuesRender) {
    const std::string out = std::string(RT_TEST_OUTPUT_DIR) + "/hierarchy_options_good.png";
    std::filesystem::create_directories(RT_TEST_OUTPUT_DIR);
    for (const char* objects : {"triangles", "meshes", "tree"}) {
        std::filesystem::remove(out);
        const StageRun r = run_stage_04({"--scene", "builtin:whitted", "--width", "16", "--height", "12", "--quiet",
                                         "--branching", "16", "--levels", "2", "--objects", objects, "--out", out});
        EXPECT_EQ(r.rc, 0) << objects << ": " << r.err;
        EXPECT_TRUE(std::filesystem::exists(out)) << objects;
    }
}

}  // namespace
}  // namespace rt
