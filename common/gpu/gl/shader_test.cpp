// Shader files: #include resolution, injected defines, errors that name the real file and line, the shared binding
// numbers, and dispatches beyond 65535 work groups.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "bindings.h"
#include "buffer.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "shader.h"

namespace fs = std::filesystem;

namespace rt::gpu {
namespace {

fs::path temp_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("rt_gpu_" + name + "_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

void write_file(const fs::path& p, const std::string& text) {
    std::ofstream out(p);
    out << text;
}

TEST(Shader, ShaderRootIsNextToTheBinary) {
    const fs::path root = shader_root();
    EXPECT_TRUE(fs::is_regular_file(root / "common" / "shaders" / "trace" / "intersect.glsl")) << root;
}

TEST(Shader, IncludesAndDefines) {
    test_context();
    const fs::path dir = temp_dir("include");
    write_file(dir / "value.glsl", "uint twice(uint x) { return 2u * x; }\n");
    write_file(dir / "again.glsl", "#include \"value.glsl\"\n");   // included twice: once only
    write_file(dir / "main.comp", R"(#version 450 core
#include "value.glsl"
#include "again.glsl"
#include "common/shaders/bindings.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = RT_BINDING_STAGE_FIRST) buffer Out { uint result[]; };
void main() {
#ifdef ENABLE_SHADOWS
    result[0] = twice(VALUE);
#else
    result[0] = 0u;
#endif
}
)");
    Program p = Program::compute(dir / "main.comp", {{"ENABLE_SHADOWS", ""}, {"VALUE", "21u"}});
    EXPECT_EQ(p.local_size(), glm::uvec3(1, 1, 1));
    Buffer out(4);
    out.bind(kBindingStageFirst);
    p.dispatch(1);
    EXPECT_EQ(out.download_value<std::uint32_t>(), 42u);
    fs::remove_all(dir);
}

TEST(Shader, CompileErrorNamesIncludedFileAndLine) {
    test_context();
    const fs::path dir = temp_dir("broken");
    write_file(dir / "helper.glsl", "// helper\nfloat ok() { return 1.0; }\nfloat broken() { return undefined_thing; }\n");
    write_file(dir / "main.comp",
               "#version 450 core\n#include \"helper.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() { ok(); }\n");
    try {
        Program::compute(dir / "main.comp");
        FAIL() << "no exception";
    } catch (const ShaderError& e) {
        const std::string what = e.what();
        std::printf("%s\n", what.c_str());
        EXPECT_NE(what.find("helper.glsl:3:"), std::string::npos) << what;
        EXPECT_NE(what.find("undefined_thing"), std::string::npos) << what;
    }
    // An error in the top file after an include: the line numbers continue correctly.
    write_file(dir / "main2.comp",
               "#version 450 core\n#include \"helper.glsl\"\nlayout(local_size_x = 1) in;\n\nvoid main() { nope(); }\n");
    try {
        Program::compute(dir / "main2.comp");
        FAIL() << "no exception";
    } catch (const ShaderError& e) {
        EXPECT_NE(std::string(e.what()).find("main2.comp:5:"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

TEST(Shader, InMemorySourceErrorAndMissingInclude) {
    test_context();
    try {
        Program::compute_source("inline.comp", "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {\n  int x = ;\n}\n");
        FAIL() << "no exception";
    } catch (const ShaderError& e) {
        EXPECT_NE(std::string(e.what()).find("inline.comp:4:"), std::string::npos) << e.what();
    }
    try {
        Program::compute_source("missing.comp", "#version 450\n\n#include \"no_such_file.glsl\"\nvoid main() {}\n");
        FAIL() << "no exception";
    } catch (const ShaderError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("missing.comp:3"), std::string::npos) << what;
        EXPECT_NE(what.find("no_such_file.glsl"), std::string::npos) << what;
    }
}

TEST(Shader, LogMappingOfOtherDrivers) {
    const std::vector<std::string> files = {"main.comp", "common/shaders/trace/intersect.glsl"};
    // Lines of included files are encoded as file * 100000 + line (Mesa misreports some source numbers).
    EXPECT_EQ(map_shader_log("1(100017) : error C1008: undefined variable \"x\"", files),
              "common/shaders/trace/intersect.glsl:17: error C1008: undefined variable \"x\"\n");
    EXPECT_EQ(map_shader_log("0:3(10): error: syntax error", files), "main.comp:3:10: error: syntax error\n");
    EXPECT_EQ(map_shader_log("ERROR: 0:100005: 'x' : undeclared", files), "common/shaders/trace/intersect.glsl:5: ERROR: 'x' : undeclared\n");
}

TEST(Shader, BindingsMatchBetweenCppAndGlsl) {
    std::ifstream in(shader_root() / "common" / "shaders" / "bindings.glsl");
    ASSERT_TRUE(in);
    std::map<std::string, unsigned> glsl;
    const std::regex def(R"(^#define\s+(RT_\w+)\s+(\d+)\s*$)");
    std::string line;
    std::smatch m;
    while (std::getline(in, line))
        if (std::regex_match(line, m, def)) glsl[m[1]] = unsigned(std::stoul(m[2]));
    const std::map<std::string, unsigned> cpp = {
        {"RT_BINDING_POSITIONS", kBindingPositions},       {"RT_BINDING_NORMALS", kBindingNormals},
        {"RT_BINDING_UVS", kBindingUvs},                   {"RT_BINDING_MATERIAL_IDS", kBindingMaterialIds},
        {"RT_BINDING_MATERIALS", kBindingMaterials},       {"RT_BINDING_LIGHTS", kBindingLights},
        {"RT_BINDING_TEXTURE_INFO", kBindingTextureInfo},  {"RT_BINDING_COUNTERS", kBindingCounters},
        {"RT_BINDING_SCAN_IN", kBindingScanIn},            {"RT_BINDING_SCAN_OUT", kBindingScanOut},
        {"RT_BINDING_SCAN_SUMS", kBindingScanSums},        {"RT_BINDING_COMPACT_FLAGS", kBindingCompactFlags},
        {"RT_BINDING_COMPACT_OFFSETS", kBindingCompactOffsets}, {"RT_BINDING_COMPACT_VALUES", kBindingCompactValues},
        {"RT_BINDING_COMPACT_OUT", kBindingCompactOut},    {"RT_BINDING_HARNESS", kBindingHarness},
        {"RT_BINDING_STAGE_FIRST", kBindingStageFirst},    {"RT_UBO_SCENE", kUboScene},
        {"RT_UBO_STAGE_FIRST", kUboStageFirst},            {"RT_TEXTURE_UNIT_TEXTURES", kTextureUnitTextures},
        {"RT_TEXTURE_UNIT_STAGE_FIRST", kTextureUnitStageFirst},
        {"RT_TEXTURE_UNIT_ENVIRONMENT", kTextureUnitEnvironment}};
    EXPECT_EQ(glsl, cpp);
}

// Thread i of n adds i + 1 to result[i] (one thread a group): on a zeroed buffer, each thread reached exactly once
// leaves result[i] = i + 1.
Program each_thread_once() {
    return Program::compute_source("each_thread.comp", R"(#version 450
#include "common/shaders/compute.glsl"
#include "common/shaders/bindings.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = RT_BINDING_STAGE_FIRST) buffer Out { uint result[]; };
uniform uint n;
void main() {
    const uint i = rt_global_index();
    if (i < n) result[i] += i + 1u;
}
)");
}

TEST(Shader, DispatchBeyond65535GroupsUsesA2DGrid) {
    test_context();
    Program p = each_thread_once();
    const std::size_t n = 70001;
    Buffer out(n * 4);
    out.clear_u32(0);
    out.bind(kBindingStageFirst);
    p.set("n", unsigned(n));
    p.dispatch_threads(n);
    const auto r = out.download_all<std::uint32_t>();
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(r[i], i + 1) << i;
}

// compute.glsl's rt_dispatch_size, for indirect dispatches, is Program::grid_for, the grid of dispatch_threads; and
// an indirect dispatch of the grid it writes reaches every thread once (here a local size of 1: 70001 groups, 2D).
TEST(Shader, IndirectDispatchSizeIsTheGridOfDispatchThreads) {
    test_context();
    Program sizes = Program::compute_source("sizes.comp", R"(#version 450
#include "common/shaders/compute.glsl"
#include "common/shaders/bindings.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = RT_BINDING_STAGE_FIRST) buffer Io { uint io[]; };   // (threads, local size) -> grid
uniform uint count;
void main() {
    const uint i = rt_global_index();
    if (i >= count) return;
    const uvec3 grid = rt_dispatch_size(io[5u * i], io[5u * i + 1u]);
    io[5u * i + 2u] = grid.x;
    io[5u * i + 3u] = grid.y;
    io[5u * i + 4u] = grid.z;
}
)");
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> cases = {
        {0, 64},    {1, 64},     {64, 64},    {65, 64},         {65535u * 64, 64}, {65535u * 64 + 1, 64},
        {70001, 1}, {65535, 1},  {65536, 1},  {0xffffffffu, 64}, {0xffffffffu, 1},  {4096, 256}};
    std::vector<std::uint32_t> io;
    for (const auto& [threads, local] : cases) io.insert(io.end(), {threads, local, 0u, 0u, 0u});
    Buffer buffer = Buffer::from(io);
    buffer.bind(kBindingStageFirst);
    sizes.set("count", unsigned(cases.size()));
    sizes.dispatch_threads(cases.size());
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const auto r = buffer.download_all<std::uint32_t>();
    for (std::size_t c = 0; c < cases.size(); ++c) {
        const glm::uvec3 want = Program::grid_for(cases[c].first, cases[c].second);
        EXPECT_EQ(glm::uvec3(r[5 * c + 2], r[5 * c + 3], r[5 * c + 4]), want)
            << cases[c].first << " threads in groups of " << cases[c].second;
    }

    Program fill = each_thread_once();
    const std::uint32_t n = 70001;
    const glm::uvec3 grid = Program::grid_for(n, 1);
    ASSERT_GT(grid.y, 1u);
    const Buffer args = Buffer::from(std::vector<std::uint32_t>{grid.x, grid.y, grid.z});
    Buffer out(std::size_t(n) * 4);
    out.clear_u32(0);
    out.bind(kBindingStageFirst);
    fill.set("n", n);
    fill.dispatch_indirect(args, 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const auto filled = out.download_all<std::uint32_t>();
    for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(filled[i], i + 1) << i;
}

TEST(Shader, CountersCarryBeyond32Bits) {
    test_context();
    Program p = Program::compute_source("counters.comp", R"(#version 450
#include "common/shaders/counters.glsl"
layout(local_size_x = 64) in;
void main() {
    rt_counter_add(RT_COUNTER_PRIMARY_RAYS, 1u);
    rt_counter_add(RT_COUNTER_INTERSECTION_TESTS, 0x10000000u);   // 2^28 per thread
}
)");
    CounterBuffer counters;
    counters.bind();
    p.dispatch(4);   // 256 threads
    const RayCounters c = counters.ray_counters();
    EXPECT_EQ(c.rays[0], 256u);
    EXPECT_EQ(c.intersection_tests, 256ull << 28);
    counters.clear();
    EXPECT_EQ(counters.read()[0], 0u);
}

TEST(Shader, GpuTimerMeasuresPhases) {
    test_context();
    GpuTimer timer;
    Buffer b(1 << 20);
    {
        auto scope = timer.scope("clear");
        b.clear_u32(7);
    }
    timer.begin("clear");
    b.clear_u32(8);
    timer.end();
    const auto r = timer.results();
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].first, "clear");
    EXPECT_GE(r[0].second, 0.0);
}

}  // namespace
}  // namespace rt::gpu
