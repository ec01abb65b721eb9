// Stage 03's own options through the stage's command line (rt::run_stage): a bad --grid-lambda, --grid-res or
// --primary is one line `03_uniform_grid: error: ...` and exit 2, before anything is rendered or written; a grid
// that would not fit the GPU's storage block is refused the same way.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "grid_renderer.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

StageRun run_stage_03(std::vector<std::string> args) {
    GridRenderer renderer;
    return run_stage_command("03_uniform_grid", renderer, std::move(args));
}

TEST(GridOptions, BadValuesAreOneLineErrorsWithExit2) {
    const std::string out = std::string(RT_TEST_OUTPUT_DIR) + "/grid_options.png";
    std::filesystem::create_directories(RT_TEST_OUTPUT_DIR);
    for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
             {"--grid-lambda", "0"}, {"--grid-lambda", "-1"}, {"--grid-lambda", "nan"}, {"--grid-res", "2,x,3"},
             {"--grid-res", "0,1,1"}, {"--grid-res", "1,1"}, {"--grid-res", "1,1,1,1"}, {"--grid-res", "2000,1,1"},
             {"--primary", "both"}}) {
        std::filesystem::remove(out);
        std::vector<std::string> args = {"--scene", "builtin:whitted", "--width", "8", "--height", "6", "--out", out};
        args.insert(args.end(), bad.begin(), bad.end());
        expect_one_line_error(run_stage_03(args), "03_uniform_grid", bad[0]);
        EXPECT_FALSE(std::filesystem::exists(out)) << bad[0] << " " << bad[1];
    }
}

TEST(GridOptions, ParseGridRes) {
    EXPECT_EQ(parse_grid_res("4,5,6"), glm::ivec3(4, 5, 6));
    EXPECT_EQ(parse_grid_res("1,1,1"), glm::ivec3(1));
    EXPECT_THROW(parse_grid_res("4,5,6 7"), std::invalid_argument);
    EXPECT_THROW(parse_grid_res(""), std::invalid_argument);
}

TEST(GridOptions, AGridBeyondTheStorageLimitIsRefusedAndWritesNothing) {
    const std::string out = std::string(RT_TEST_OUTPUT_DIR) + "/grid_too_big.png";
    std::filesystem::create_directories(RT_TEST_OUTPUT_DIR);
    std::filesystem::remove(out);
    const StageRun r = run_stage_03({"--scene", "builtin:whitted", "--width", "8", "--height", "6", "--out", out,
                                "--grid-res", "1024,1024,1024"});
    expect_one_line_error(r, "03_uniform_grid", "storage block limit");
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace rt
