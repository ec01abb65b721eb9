// A shader that does not compile: the first line of the error says what failed and how many errors, the compiler's
// lines (with real file names and lines) follow.
#include <gtest/gtest.h>

#include <string>

#include "common/gpu/testing/gpu_test_context.h"
#include "shader.h"

namespace rt::gpu {
namespace {

TEST(Shader, CompileErrorFirstLineSaysWhatFailed) {
    test_context();
    try {
        Program::compute_source("two_errors.comp",
                                "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {\n  float a = missing_one;\n"
                                "  float b = missing_two;\n}\n");
        FAIL() << "no exception";
    } catch (const ShaderError& e) {
        const std::string what = e.what();
        const std::string first = what.substr(0, what.find('\n'));
        EXPECT_EQ(first, "cannot compile compute shader two_errors.comp: 2 error(s)") << what;
        EXPECT_NE(what.find("two_errors.comp:4:"), std::string::npos) << what;
        EXPECT_NE(what.find("two_errors.comp:5:"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace rt::gpu
