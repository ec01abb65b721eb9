// Context creation on the headless backends: each must give a GL 4.5 core context (llvmpipe on the CI machine).
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include "context.h"
#include "common/gpu/testing/gpu_test_context.h"

namespace rt::gpu {
namespace {

void expect_usable(const GpuContext& c) {
    EXPECT_GE(c.gl_major() * 10 + c.gl_minor(), 45) << c.version();
    EXPECT_FALSE(c.renderer().empty());
    // A trivial GL call works through the loaded pointers.
    GLint groups = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &groups);
    EXPECT_GE(groups, 65535);
    check_gl("context query");
}

TEST(GpuContext, EglHeadless) {
    GpuContext c = create_headless_context("egl");
    EXPECT_TRUE(c.backend() == "egl-surfaceless" || c.backend() == "egl-device") << c.backend();
    expect_usable(c);
    if (c.backend() == "egl-surfaceless") {
        EXPECT_NE(c.renderer().find("llvmpipe"), std::string::npos) << c.renderer();
    }
    std::printf("EGL: %s | %s | %s\n", c.backend().c_str(), c.renderer().c_str(), c.version().c_str());
}

TEST(GpuContext, OSMesa) {
    GpuContext c = create_headless_context("osmesa");
    EXPECT_EQ(c.backend(), "osmesa");
    expect_usable(c);
    EXPECT_NE(c.renderer().find("llvmpipe"), std::string::npos) << c.renderer();
    std::printf("OSMesa: %s | %s\n", c.renderer().c_str(), c.version().c_str());
}

TEST(GpuContext, SwitchingBetweenContextsReloadsFunctions) {
    GpuContext a = create_headless_context("egl");
    GpuContext b = create_headless_context("osmesa");
    a.make_current();
    expect_usable(a);
    b.make_current();
    expect_usable(b);
}

TEST(GpuContext, UnknownBackendThrows) {
    EXPECT_THROW(create_headless_context("vulkan"), std::runtime_error);
}

TEST(GpuContext, CliOptions) {
    CLI::App app;
    GpuOptions options;
    add_gpu_options(app, options);
    const char* argv[] = {"stage", "--backend", "osmesa"};
    app.parse(3, argv);
    EXPECT_EQ(options.backend, "osmesa");
    EXPECT_FALSE(options.window);
    CLI::App app2;
    GpuOptions options2;
    add_gpu_options(app2, options2);
    const char* bad[] = {"stage", "--backend", "cuda"};
    EXPECT_THROW(app2.parse(3, bad), CLI::ValidationError);
}

#ifndef RT_HAVE_GLFW
TEST(GpuContext, WindowRefusedInPortableBuild) {
    GpuOptions o;
    o.window = true;
    EXPECT_THROW(create_context(o), std::runtime_error);
}
#endif

TEST(GpuContext, GlErrorsBecomeExceptions) {
    test_context();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 123456);   // not a buffer name: GL_INVALID_OPERATION
    try {
        check_gl("binding a bogus buffer");
        FAIL() << "no exception";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("binding a bogus buffer"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("GL_INVALID_OPERATION"), std::string::npos) << e.what();
    }
    check_gl("after the error was drained");
}

}  // namespace
}  // namespace rt::gpu
