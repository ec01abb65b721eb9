// The other half of a GPU stage (gpu_stage.h), beside its traversal: how a sample finds its primary hits. Stage 02's
// RasterizedPrimary (02_raster_hybrid/rasterized_primary.h) rasterizes them into a G-buffer; TracedPrimary traces the
// camera rays through the stage's traversal (03's --primary trace). Either way the wavefront pipeline then shades the
// hits and traces every bounce after them.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "traversal.h"
#include "wavefront.h"

namespace rt::gpu {

class PrimaryVisibility {
public:
    virtual ~PrimaryVisibility() = default;
    // One sample through `offset` in each pixel (0.5, 0.5 = the centre): its primary hits, then the pipeline's
    // shading and bounces.
    virtual void render_sample(const FrameInputs& frame, Wavefront& wavefront, glm::vec2 offset) = 0;
    // True when the primary rays are rasterized, not traced (rays.rasterized, and left out of mrays_per_s).
    virtual bool rasterized() const = 0;
    // The programs of its own passes, for the stats' `programs`.
    virtual std::vector<std::string> programs() const { return {}; }
};

// Camera rays traced through the stage's traversal.
class TracedPrimary final : public PrimaryVisibility {
public:
    void render_sample(const FrameInputs& frame, Wavefront& wavefront, glm::vec2 offset) override {
        frame.gpu_scene.bind();
        wavefront.trace_camera_sample(offset);
    }
    bool rasterized() const override { return false; }
};

}  // namespace rt::gpu
