// Rasterized primary visibility, the first pass of the stages that rasterize instead of tracing primary rays
// (02, and the ray-hierarchy stages 04-05, after Roger, Assarsson & Holzschuch 2007 and Reis):
//  1. render(): rasterize the scene into a G-buffer. Each pixel gets the index of the nearest triangle at its sample
//     position (R32UI, triangle + 1, 0 = none) and its depth (32-bit float, reversed), for the price of one draw
//     call (shaders/gbuffer.vert, .frag). That is what a primary ray through the pixel finds, except on
//     edges and silhouettes, where the fill rule and subpixel snapping decide (see 2.).
//  2. shade_sample(): turn each pixel into a primary hit of the wavefront pipeline (shaders/primary_hits.comp) and
//     let the pipeline shade them and trace every bounce.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/scene/scene.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/gl/shader.h"
#include "common/gpu/pipeline/wavefront.h"

namespace rt::gpu {

class GBuffer {
public:
    // The pass that turns pixels into primary hits (exercise 02.primary_hits), by its name in the stats.
    static constexpr const char* kPrimaryHitsProgram = "02_raster_hybrid/shaders/primary_hits.comp";

    GBuffer();   // needs a current GL context
    GBuffer(const GBuffer&) = delete;
    GBuffer& operator=(const GBuffer&) = delete;
    ~GBuffer();

    // Rasterizes the uploaded scene as `camera` sees it into a width x height G-buffer, each pixel sampled at
    // `offset` inside it (0.5, 0.5 = the centre). `bounds` places the near/far planes.
    void render(const GpuScene& scene, const Camera& camera, const Bounds& bounds, int width, int height,
                glm::vec2 offset);

    // Triangle index + 1 per pixel (0 = none), row 0 at the top. Waits for the GPU.
    std::vector<std::uint32_t> read_triangle_ids() const;
    GLuint triangle_id_texture() const { return ids_; }

    // Pass 2 and on: the pixels of the G-buffer become the pipeline's primary hits (the camera ray of each pixel
    // intersected with the triangles of its 3x3 neighbourhood in the G-buffer, the closest kept, ties to the lowest
    // id: brute force's hit, see shaders/primary_hits.comp; no hit adds the background), in the pipeline's primary
    // order, and Wavefront::shade_sample does the rest of the sample. Compiled with the
    // pipeline's defines. The pipeline's begin_frame() must have run and the scene must be bound.
    // With cut-outs (ENABLE_CUTOUTS) it also hands the pipeline shaders/deferred_rays.comp: pixels whose candidate
    // may be transparent have their camera ray traced instead.
    void shade_sample(Wavefront& wavefront, glm::vec2 offset);
    // The programs shade_sample compiled for the pipeline's current defines (the stats' `programs`).
    std::vector<std::string> programs() const;

private:
    void resize(int width, int height);
    Program program_;
    Program primary_hits_, deferred_rays_;
    std::string primary_hits_key_;
    GLuint vao_ = 0, fbo_ = 0, ids_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace rt::gpu
