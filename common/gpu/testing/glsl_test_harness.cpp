#include "glsl_test_harness.h"

#include <stdexcept>

#include "common/gpu/gl/bindings.h"

namespace rt::gpu {

const char* GlslTestHarness::prelude() {
    return R"(#version 450 core
#include "common/shaders/bindings.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = RT_BINDING_HARNESS) buffer HarnessData { uint harness_data[]; };
uniform uint harness_count;
uniform uint harness_in_stride;
uniform uint harness_out_stride;
uniform uint harness_out_base;
uint harness_index;
uint in_u(uint k) { return harness_data[harness_index * harness_in_stride + k]; }
int in_i(uint k) { return int(in_u(k)); }
float in_f(uint k) { return uintBitsToFloat(in_u(k)); }
vec2 in_vec2(uint k) { return vec2(in_f(k), in_f(k + 1u)); }
vec3 in_vec3(uint k) { return vec3(in_f(k), in_f(k + 1u), in_f(k + 2u)); }
vec4 in_vec4(uint k) { return vec4(in_f(k), in_f(k + 1u), in_f(k + 2u), in_f(k + 3u)); }
void out_u(uint k, uint v) { harness_data[harness_out_base + harness_index * harness_out_stride + k] = v; }
void out_i(uint k, int v) { out_u(k, uint(v)); }
void out_b(uint k, bool v) { out_u(k, v ? 1u : 0u); }
void out_f(uint k, float v) { out_u(k, floatBitsToUint(v)); }
void out_vec2(uint k, vec2 v) { out_f(k, v.x); out_f(k + 1u, v.y); }
void out_vec3(uint k, vec3 v) { out_f(k, v.x); out_f(k + 1u, v.y); out_f(k + 2u, v.z); }
void out_vec4(uint k, vec4 v) { out_f(k, v.x); out_f(k + 1u, v.y); out_f(k + 2u, v.z); out_f(k + 3u, v.w); }
)";
}

GlslTestHarness::GlslTestHarness(const std::string& name, const std::string& body, const ShaderDefines& defines) {
    // The body's lines keep their numbers in error messages: the prelude is its own "file" through #line.
    const std::string text = std::string(prelude()) + "#line 1\n" + body +
                             "\nvoid main() {\n"
                             "    harness_index = gl_GlobalInvocationID.x;\n"
                             "    if (harness_index >= harness_count) return;\n"
                             "    test_main();\n"
                             "}\n";
    program_ = Program::compute_source(name, text, defines);
}

std::vector<std::uint32_t> GlslTestHarness::run(const std::vector<std::uint32_t>& input, std::size_t count,
                                                std::size_t in_stride, std::size_t out_stride,
                                                const std::function<void()>& before) {
    if (input.size() < count * in_stride) throw std::invalid_argument("GlslTestHarness::run: input too short");
    const std::size_t in_words = count * in_stride;
    const std::size_t total = in_words + count * out_stride;
    data_.resize(total * 4);
    if (in_words) data_.upload(input.data(), in_words * 4);
    data_.bind(kBindingHarness);
    program_.set("harness_count", unsigned(count));
    program_.set("harness_in_stride", unsigned(in_stride));
    program_.set("harness_out_stride", unsigned(out_stride));
    program_.set("harness_out_base", unsigned(in_words));
    if (before) before();
    program_.dispatch(unsigned((count + 63) / 64));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    check_gl("GlslTestHarness::run " + program_.name());
    return data_.download<std::uint32_t>(count * out_stride, in_words);
}

}  // namespace rt::gpu
