// C++ and GLSL agree on where data lives: every SSBO/UBO binding of bindings.h is the one the shaders declare, and
// every struct the two sides share (gpu_scene.h, wavefront.h) has the same member offsets and array stride. The GLSL
// side is compiled as it is (scene.glsl, counters.glsl, wavefront.glsl, the scan and compaction passes) and read back
// through GL's program interface queries (GL_BUFFER_BINDING, GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE), so a change on
// one side only fails here, not as a silently wrong image.
#include <gtest/gtest.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "bindings.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "shader.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {
namespace {

// Programs that declare the shared data and touch each block so that the linker keeps it: one for the scene and the
// counters, one for the wavefront queues (a compute shader may use only 16 SSBOs). The Test* blocks pin the bare
// numbers of bindings.glsl that no shared declaration uses.
const char* kSceneDeclarations = R"(
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/counters.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = RT_BINDING_HARNESS) buffer TestHarness { uint test_out[]; };
layout(std430, binding = RT_BINDING_STAGE_FIRST) buffer TestStageFirst { uint test_stage_first[]; };
layout(std140, binding = RT_UBO_STAGE_FIRST) uniform TestUboStageFirst { uint test_ubo_stage_first; };
layout(binding = RT_TEXTURE_UNIT_STAGE_FIRST) uniform usampler2D test_texture_stage_first;
void main() {
    float f = rt_positions[0].x + rt_normals[0].x + rt_uvs[0].x + float(rt_material_ids[0]) + rt_materials[0].ior
            + rt_lights[0].range + rt_srgb_lut[0] + float(rt_texture_info(0).first) + float(rt_counters[0])
            + rt_camera.yfov + float(rt_triangle_count)
            + float(test_stage_first[0] + test_ubo_stage_first) + float(textureSize(test_texture_stage_first, 0).x);
    test_out[0] = floatBitsToUint(f);
}
)";

const char* kWavefrontDeclarations = R"(
#define RECORD_TESTS_PER_PIXEL 1
#include "common/shaders/wavefront/wavefront.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = WF_BINDING_RESULTS) buffer WfTraceResults { WavefrontTraceResult wf_trace_results[]; };
layout(std430, binding = WF_BINDING_TRAVERSAL_FIRST) buffer TestTraversalFirst { uint test_traversal_first[]; };
void main() {
    float f = wf_rays_in[0].tmax + wf_hits[0].t + wf_ray_slots[0].tmax + float(wf_flags[0]) + float(wf_radiance[0])
            + wf_trace_results[0].t + wf_image[0].x + float(wf_tests_per_pixel[0]) + float(test_traversal_first[0]);
    wf_image[0].y = f;
}
)";

GLuint compiled(const char* name, const char* source) {
    static std::map<std::string, Program> programs;
    test_context();
    auto it = programs.find(name);
    if (it == programs.end())
        it = programs.emplace(name, Program::compute_source(name, source, {{"RT_INTERSECT_METHOD", "RT_INTERSECT_WATERTIGHT"},
                                                                           {"COUNT_TESTS", "1"}})).first;
    return it->second.id();
}
GLuint scene_program() { return compiled("bindings_test scene", kSceneDeclarations); }
GLuint wavefront_program() { return compiled("bindings_test wavefront", kWavefrontDeclarations); }

GLint property(GLuint program, GLenum interface, GLuint index, GLenum prop) {
    GLint value = -1;
    glGetProgramResourceiv(program, interface, index, 1, &prop, 1, nullptr, &value);
    return value;
}

// GL_BUFFER_BINDING of a named SSBO or UBO (-1 when the program has no such active block).
GLint block_binding(GLuint program, GLenum interface, const char* block) {
    const GLuint index = glGetProgramResourceIndex(program, interface, block);
    return index == GL_INVALID_INDEX ? -1 : property(program, interface, index, GL_BUFFER_BINDING);
}

struct Layout {
    GLint offset = -1, stride = -1;
};

// The members of a block as GLSL laid them out: name -> offset and the stride of the block's array (0 for none).
// `variables` is GL_BUFFER_VARIABLE for SSBOs, GL_UNIFORM for UBOs.
std::map<std::string, Layout> block_members(GLuint program, GLenum block_interface, GLenum variables,
                                            const char* block) {
    std::map<std::string, Layout> out;
    const GLuint index = glGetProgramResourceIndex(program, block_interface, block);
    if (index == GL_INVALID_INDEX) return out;
    const GLint count = property(program, block_interface, index, GL_NUM_ACTIVE_VARIABLES);
    std::vector<GLint> members(std::size_t(std::max(count, 0)));
    const GLenum active = GL_ACTIVE_VARIABLES;
    glGetProgramResourceiv(program, block_interface, index, 1, &active, count, nullptr, members.data());
    for (GLint m : members) {
        char name[256] = {};
        glGetProgramResourceName(program, variables, GLuint(m), sizeof(name), nullptr, name);
        Layout l;
        l.offset = property(program, variables, GLuint(m), GL_OFFSET);
        // The element stride of the block's array: GL_ARRAY_STRIDE when the variable is the array ("rt_uvs[0]"),
        // GL_TOP_LEVEL_ARRAY_STRIDE when it is a member of an array of structs ("rt_materials[0].ior").
        if (variables == GL_BUFFER_VARIABLE)
            l.stride = property(program, variables, GLuint(m),
                                std::string(name).find('.') == std::string::npos ? GL_ARRAY_STRIDE
                                                                                  : GL_TOP_LEVEL_ARRAY_STRIDE);
        out[name] = l;
    }
    return out;
}

// Compares a block's members with the C++ side: `expected` maps each GLSL member name to its C++ offset (and, for
// SSBOs, the C++ array stride, i.e. sizeof the element). Every GLSL member must be in `expected` and vice versa, so
// a member added on one side only fails too.
void expect_layout(GLuint program, GLenum block_interface, GLenum variables, const char* block,
                   const std::map<std::string, Layout>& expected) {
    const std::map<std::string, Layout> glsl = block_members(program, block_interface, variables, block);
    ASSERT_FALSE(glsl.empty()) << block << " is not an active block of the test program";
    for (const auto& [name, layout] : glsl) {
        const auto it = expected.find(name);
        if (it == expected.end()) {
            ADD_FAILURE() << block << ": GLSL member " << name << " has no C++ counterpart in this test";
            continue;
        }
        EXPECT_EQ(layout.offset, it->second.offset) << block << ": offset of " << name;
        if (variables == GL_BUFFER_VARIABLE) {
            EXPECT_EQ(layout.stride, it->second.stride) << block << ": stride of " << name;
        }
    }
    for (const auto& [name, layout] : expected)
        EXPECT_TRUE(glsl.count(name)) << block << ": C++ expects " << name << ", which GLSL does not declare";
}

// The members of an SSBO array of structs `array` of element type T: "array[0].member" -> offset, sizeof(T).
template <class T>
std::map<std::string, Layout> array_of(const std::string& array, std::size_t base,
                                       const std::vector<std::pair<std::string, std::size_t>>& members) {
    std::map<std::string, Layout> out;
    for (const auto& [name, offset] : members)
        out[array + "[0]." + name] = {GLint(base + offset), GLint(sizeof(T))};
    return out;
}

TEST(Bindings, SceneAndWavefrontSsbosAreWhereTheCppSideBindsThem) {
    const std::map<std::string, unsigned> ssbos = {
        {"ScenePositions", kBindingPositions},       {"SceneNormals", kBindingNormals},
        {"SceneUvs", kBindingUvs},                   {"SceneMaterialIds", kBindingMaterialIds},
        {"SceneMaterials", kBindingMaterials},       {"SceneLights", kBindingLights},
        {"SceneTextures", kBindingTextureInfo},      {"RtCounters", kBindingCounters},
        {"WfRaysIn", kBindingWavefrontRaysIn},       {"WfHits", kBindingWavefrontHits},
        {"WfRaySlots", kBindingWavefrontRaySlots},   {"WfFlags", kBindingWavefrontFlags},
        {"WfRadiance", kBindingWavefrontRadiance},   {"WfTraceResults", kBindingWavefrontResults},
        {"WfImage", kBindingWavefrontImage},         {"WfTestsPerPixel", kBindingWavefrontTestsPerPixel},
        {"TestHarness", kBindingHarness},            {"TestStageFirst", kBindingStageFirst},
        {"TestTraversalFirst", kBindingWavefrontTraversalFirst}};
    for (const auto& [block, binding] : ssbos) {
        const GLuint p = block.starts_with("Wf") || block == "TestTraversalFirst" ? wavefront_program() : scene_program();
        EXPECT_EQ(block_binding(p, GL_SHADER_STORAGE_BLOCK, block.c_str()), GLint(binding)) << block;
    }
}

TEST(Bindings, UniformBlocksAndTextureUnitsAreWhereTheCppSideBindsThem) {
    const GLuint p = scene_program();
    EXPECT_EQ(block_binding(p, GL_UNIFORM_BLOCK, "SceneBlock"), GLint(kUboScene));
    EXPECT_EQ(block_binding(p, GL_UNIFORM_BLOCK, "TestUboStageFirst"), GLint(kUboStageFirst));
    // A sampler's binding is its uniform value: the texture unit.
    const std::map<std::string, unsigned> samplers = {{"test_texture_stage_first", kTextureUnitStageFirst}};
    for (const auto& [sampler, unit] : samplers) {
        GLint value = -1;
        glGetUniformiv(p, glGetUniformLocation(p, sampler.c_str()), &value);
        EXPECT_EQ(value, GLint(unit)) << sampler;
    }
    check_gl("sampler units");
}

TEST(Bindings, ScanAndCompactionPassesUseTheirBindings) {
    test_context();
    struct Case {
        Program program;
        std::map<std::string, unsigned> blocks;
    };
    std::vector<Case> cases;
    cases.push_back({Program::compute("common/shaders/primitives/scan_block.comp"),
                     {{"ScanIn", kBindingScanIn}, {"ScanOut", kBindingScanOut}, {"ScanSums", kBindingScanSums}}});
    cases.push_back({Program::compute("common/shaders/primitives/scan_add.comp"),
                     {{"ScanOut", kBindingScanOut}, {"ScanSums", kBindingScanSums}}});
    cases.push_back({Program::compute("common/shaders/primitives/compact_scatter.comp", {{"COMPACT_VALUES", "1"}}),
                     {{"Flags", kBindingCompactFlags}, {"Offsets", kBindingCompactOffsets},
                      {"Values", kBindingCompactValues}, {"Out", kBindingCompactOut}}});
    for (const Case& c : cases)
        for (const auto& [block, binding] : c.blocks)
            EXPECT_EQ(block_binding(c.program.id(), GL_SHADER_STORAGE_BLOCK, block.c_str()), GLint(binding))
                << c.program.name() << ": " << block;
}

TEST(Bindings, SceneStructsHaveTheCppLayout) {
    const GLuint p = scene_program();
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "ScenePositions",
                  {{"rt_positions[0]", {0, GLint(sizeof(glm::vec4))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "SceneNormals",
                  {{"rt_normals[0]", {0, GLint(sizeof(glm::vec4))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "SceneUvs", {{"rt_uvs[0]", {0, GLint(sizeof(glm::vec2))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "SceneMaterialIds",
                  {{"rt_material_ids[0]", {0, GLint(sizeof(std::uint32_t))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "SceneMaterials",
                  array_of<GpuMaterial>("rt_materials", 0,
                                        {{"base_color", offsetof(GpuMaterial, base_color)},
                                         {"emissive", offsetof(GpuMaterial, emissive)},
                                         {"base_color_texture", offsetof(GpuMaterial, base_color_texture)},
                                         {"specular_color", offsetof(GpuMaterial, specular_color)},
                                         {"metallic", offsetof(GpuMaterial, metallic)},
                                         {"roughness", offsetof(GpuMaterial, roughness)},
                                         {"transmission", offsetof(GpuMaterial, transmission)},
                                         {"ior", offsetof(GpuMaterial, ior)},
                                         {"specular", offsetof(GpuMaterial, specular)},
                                         {"attenuation", offsetof(GpuMaterial, attenuation)},
                                         {"thickness", offsetof(GpuMaterial, thickness)},
                                         {"normal_texture", offsetof(GpuMaterial, normal_texture)},
                                         {"normal_scale", offsetof(GpuMaterial, normal_scale)},
                                         {"alpha_mode", offsetof(GpuMaterial, alpha_mode)},
                                         {"alpha_cutoff", offsetof(GpuMaterial, alpha_cutoff)},
                                         {"metallic_roughness_texture",
                                          offsetof(GpuMaterial, metallic_roughness_texture)},
                                         {"emissive_texture", offsetof(GpuMaterial, emissive_texture)},
                                         {"transmission_texture", offsetof(GpuMaterial, transmission_texture)},
                                         {"material_pad1", offsetof(GpuMaterial, material_pad1)},

                                         {"base_color_uv_matrix", offsetof(GpuMaterial, base_color_uv_matrix)},
                                         {"normal_uv_matrix", offsetof(GpuMaterial, normal_uv_matrix)},
                                         {"base_color_uv_offset", offsetof(GpuMaterial, base_color_uv_offset)},
                                         {"normal_uv_offset", offsetof(GpuMaterial, normal_uv_offset)}}));
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "SceneLights",
                  array_of<GpuLight>("rt_lights", 0,
                                     {{"color", offsetof(GpuLight, color)},
                                      {"type", offsetof(GpuLight, type)},
                                      {"position", offsetof(GpuLight, position)},
                                      {"intensity", offsetof(GpuLight, intensity)},
                                      {"direction", offsetof(GpuLight, direction)},
                                      {"range", offsetof(GpuLight, range)},
                                      {"inner_cone", offsetof(GpuLight, inner_cone)},
                                      {"outer_cone", offsetof(GpuLight, outer_cone)},
                                      {"cos_inner", offsetof(GpuLight, cos_inner)},
                                      {"cos_outer", offsetof(GpuLight, cos_outer)}}));
    // GpuScene uploads the two 256-float tables (sRGB decode, alpha) first, then the texture words: one
    // GpuTextureInfo (4 words) per texture, then the texels (scene.glsl reads both through rt_texture_words).
    static_assert(sizeof(GpuTextureInfo) == 4 * sizeof(std::uint32_t));
    constexpr std::size_t kTables = 2 * 256 * sizeof(float);
    std::map<std::string, Layout> textures;
    textures["rt_srgb_lut[0]"] = {0, GLint(sizeof(float))};
    textures["rt_alpha_lut[0]"] = {GLint(256 * sizeof(float)), GLint(sizeof(float))};
    textures["rt_texture_words[0]"] = {GLint(kTables), GLint(sizeof(std::uint32_t))};
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "SceneTextures", textures);
    // 64-bit counters as (lo, hi) uint pairs (CounterBuffer).
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "RtCounters",
                  {{"rt_counters[0]", {0, GLint(sizeof(std::uint32_t))}}});
}

TEST(Bindings, SceneUniformBlockHasTheCppLayout) {
    const GLuint p = scene_program();
    std::map<std::string, Layout> expected;
    const std::vector<std::pair<std::string, std::size_t>> camera = {
        {"position", offsetof(GpuCamera, position)}, {"projection", offsetof(GpuCamera, projection)},
        {"right", offsetof(GpuCamera, right)},       {"tan_half_fov", offsetof(GpuCamera, tan_half_fov)},
        {"up", offsetof(GpuCamera, up)},             {"aspect", offsetof(GpuCamera, aspect)},
        {"forward", offsetof(GpuCamera, forward)},   {"xmag", offsetof(GpuCamera, xmag)},
        {"ymag", offsetof(GpuCamera, ymag)},         {"znear", offsetof(GpuCamera, znear)},
        {"zfar", offsetof(GpuCamera, zfar)},         {"yfov", offsetof(GpuCamera, yfov)}};
    for (const auto& [name, offset] : camera)
        expected["rt_camera." + name] = {GLint(offsetof(GpuSceneBlock, camera) + offset), -1};
    expected["rt_background"] = {GLint(offsetof(GpuSceneBlock, background)), -1};
    expected["rt_triangle_count"] = {GLint(offsetof(GpuSceneBlock, triangle_count)), -1};
    expected["rt_material_count"] = {GLint(offsetof(GpuSceneBlock, material_count)), -1};
    expected["rt_light_count"] = {GLint(offsetof(GpuSceneBlock, light_count)), -1};
    expected["rt_texture_count"] = {GLint(offsetof(GpuSceneBlock, texture_count)), -1};
    expected["rt_area_light_count"] = {GLint(offsetof(GpuSceneBlock, area_light_count)), -1};
    expected["rt_environment_rotation"] = {GLint(offsetof(GpuSceneBlock, environment_rotation)), -1};
    expected["rt_environment_pad"] = {GLint(offsetof(GpuSceneBlock, environment_pad)), -1};
    expect_layout(p, GL_UNIFORM_BLOCK, GL_UNIFORM, "SceneBlock", expected);
    // And the whole block is as big as the C++ struct uploaded into it.
    const GLuint block = glGetProgramResourceIndex(p, GL_UNIFORM_BLOCK, "SceneBlock");
    ASSERT_NE(block, GL_INVALID_INDEX);
    EXPECT_EQ(property(p, GL_UNIFORM_BLOCK, block, GL_BUFFER_DATA_SIZE), GLint(sizeof(GpuSceneBlock)));
}

TEST(Bindings, WavefrontQueuesHaveTheCppLayout) {
    const GLuint p = wavefront_program();
    const std::vector<std::pair<std::string, std::size_t>> ray = {
        {"origin", offsetof(WavefrontRay, origin)},       {"tmax", offsetof(WavefrontRay, tmax)},
        {"direction", offsetof(WavefrontRay, direction)}, {"pixel", offsetof(WavefrontRay, pixel)},
        {"weight", offsetof(WavefrontRay, weight)},       {"depth_kind", offsetof(WavefrontRay, depth_kind)},
        {"path", offsetof(WavefrontRay, path)},           {"light", offsetof(WavefrontRay, light)},
        {"light_sample", offsetof(WavefrontRay, light_sample)},          {"pad1", offsetof(WavefrontRay, pad1)}};
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfRaysIn",
                  array_of<WavefrontRay>("wf_rays_in", 0, ray));
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfRaySlots",
                  array_of<WavefrontRay>("wf_ray_slots", 0, ray));
    std::vector<std::pair<std::string, std::size_t>> hit = {{"triangle", offsetof(WavefrontHit, triangle)},
                                                            {"t", offsetof(WavefrontHit, t)},
                                                            {"u", offsetof(WavefrontHit, u)},
                                                            {"v", offsetof(WavefrontHit, v)}};
    for (const auto& [name, offset] : ray) hit.emplace_back("ray." + name, offsetof(WavefrontHit, ray) + offset);
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfHits", array_of<WavefrontHit>("wf_hits", 0, hit));
    // The trace pass' results (the shadow pass writes a uint per ray to the same binding, shadow.comp).
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfTraceResults",
                  array_of<WavefrontTraceResult>("wf_trace_results", 0,
                                                 {{"triangle", offsetof(WavefrontTraceResult, triangle)},
                                                  {"t", offsetof(WavefrontTraceResult, t)},
                                                  {"u", offsetof(WavefrontTraceResult, u)},
                                                  {"v", offsetof(WavefrontTraceResult, v)}}));
    // Per pixel: 9 fixed-point limbs of radiance (kRadianceBytesPerPixel in wavefront.cpp), a vec4 of the image, a
    // test count; per output slot a flag.
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfRadiance",
                  {{"wf_radiance[0]", {0, GLint(sizeof(std::uint32_t))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfImage", {{"wf_image[0]", {0, GLint(sizeof(glm::vec4))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfTestsPerPixel",
                  {{"wf_tests_per_pixel[0]", {0, GLint(sizeof(std::uint32_t))}}});
    expect_layout(p, GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "WfFlags",
                  {{"wf_flags[0]", {0, GLint(sizeof(std::uint32_t))}}});
}

}  // namespace
}  // namespace rt::gpu
