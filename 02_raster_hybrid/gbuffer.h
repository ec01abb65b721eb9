// Pass 1 of stage 02: rasterize the scene into a G-buffer. Each pixel gets the index of the nearest triangle at
// its sample position (R32UI, triangle + 1, 0 = none) and its depth (32-bit float, reversed). That is exactly
// what a primary ray through the pixel would find (Roger, Assarsson & Holzschuch 2007; Reis), for the price of one
// draw call. Shaders: shaders/gbuffer.vert and gbuffer.frag.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "common/gpu/gpu_scene.h"
#include "common/gpu/shader.h"
#include "common/scene/scene.h"

namespace rt {

class GBuffer {
public:
    GBuffer();   // needs a current GL context
    GBuffer(const GBuffer&) = delete;
    GBuffer& operator=(const GBuffer&) = delete;
    ~GBuffer();

    // Rasterizes the uploaded scene as `camera` sees it into a width x height G-buffer, each pixel sampled at
    // `offset` inside it (0.5, 0.5 = the centre). `bounds` places the near/far planes.
    void render(const gpu::GpuScene& scene, const Camera& camera, const Bounds& bounds, int width, int height,
                glm::vec2 offset);

    // Triangle index + 1 per pixel (0 = none), row 0 at the top. Waits for the GPU.
    std::vector<std::uint32_t> read_triangle_ids() const;
    GLuint triangle_id_texture() const { return ids_; }

private:
    void resize(int width, int height);
    gpu::Program program_;
    GLuint vao_ = 0, fbo_ = 0, ids_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace rt
