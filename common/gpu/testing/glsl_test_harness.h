// A small harness to run GLSL routines on the GPU and compare them with their C++ twins (glsl_twins_test.cpp).
//
// The test body is GLSL that #includes what it tests and defines `void test_main()`; the harness adds, before it,
// `#version 450 core`, a 64-wide local size and accessors to one SSBO (binding RT_BINDING_HARNESS) that holds the
// input records followed by the output records, as 32-bit words:
//     uint  harness_index;                   // the record this invocation handles
//     uint  in_u(k); int in_i(k); float in_f(k); vec2 in_vec2(k); vec3 in_vec3(k); vec4 in_vec4(k)
//     void  out_u(k, v); out_i; out_f; out_vec2; out_vec3; out_vec4; out_b(k, bool)
// where k is the word offset inside the record. Example:
//     GlslTestHarness h("dot", "#include \"common/shaders/trace/rt_math.glsl\"\n"
//                              "void test_main() { out_f(0, rt_dot(in_vec3(0), in_vec3(3))); }");
//     Words in; in << glm::vec3(1, 2, 3) << glm::vec3(4, 5, 6);
//     auto out = h.run(in.words, 1, 6, 1);   // out[0] = bits of 32.0f
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/gpu/gl/buffer.h"
#include "common/gpu/gl/shader.h"

namespace rt::gpu {

// Packs values as 32-bit words (floats by their bits).
struct Words {
    std::vector<std::uint32_t> words;
    Words& operator<<(std::uint32_t v) { words.push_back(v); return *this; }
    Words& operator<<(std::int32_t v) { words.push_back(std::uint32_t(v)); return *this; }
    Words& operator<<(bool v) { words.push_back(v ? 1u : 0u); return *this; }
    Words& operator<<(float v) {
        std::uint32_t u;
        std::memcpy(&u, &v, 4);
        words.push_back(u);
        return *this;
    }
    Words& operator<<(const glm::vec2& v) { return *this << v.x << v.y; }
    Words& operator<<(const glm::vec3& v) { return *this << v.x << v.y << v.z; }
    Words& operator<<(const glm::vec4& v) { return *this << v.x << v.y << v.z << v.w; }
};

// Reads record `i`, word `k` of an output as float / int / vec3.
inline float word_f(const std::vector<std::uint32_t>& w, std::size_t index) {
    float f;
    std::memcpy(&f, &w[index], 4);
    return f;
}

class GlslTestHarness {
public:
    GlslTestHarness(const std::string& name, const std::string& body, const ShaderDefines& defines = {});
    // Runs `count` invocations. input holds count * in_stride words; returns count * out_stride words.
    // `before` runs after the harness buffer is bound and before the dispatch (bind a GpuScene there, say).
    std::vector<std::uint32_t> run(const std::vector<std::uint32_t>& input, std::size_t count, std::size_t in_stride,
                                   std::size_t out_stride, const std::function<void()>& before = {});
    const Program& program() const { return program_; }

    static const char* prelude();

private:
    Program program_;
    Buffer data_;
};

}  // namespace rt::gpu
