// Stage 04's own options through the stage's command line (rt::run_stage): a bad --branching, --levels or
// --objects is one line `04_ray_hierarchy: error: ...` and exit 2, before anything is rendered or written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/app/driver.h"
#include "ray_hierarchy_renderer.h"

namespace rt {
namespace {

struct StageRun {
    int rc;
    std::string err;
};

StageRun run_stage_04(std::vector<std::string> args) {
    args.insert(args.begin(), "04_ray_hierarchy");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    RayHierarchyRenderer renderer;
    ::testing::internal::CaptureStderr();
    const int rc = run_stage("04_ray_hierarchy", int(argv.size()), argv.data(), renderer);
    return {rc, ::testing::internal::GetCapturedStderr()};
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
        const StageRun r = run_stage_04(args);
        EXPECT_EQ(r.rc, 2) << r.err;
        EXPECT_EQ(r.err.rfind("04_ray_hierarchy: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(bad[0]), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
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
