// Stage 03: the first acceleration structure, a uniform grid (uniform_grid.h explains it; gpu_grid.h builds it on
// the GPU every frame; shaders/grid.glsl walks it with the 3D-DDA). Everything else is stage 02's: the wavefront
// pipeline, the shading, and (with the default --primary raster) the G-buffer for primary rays, so 02 -> 03 changes
// only the traversal: brute force becomes the grid, and the image and every hit stay exactly the same.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/gpu/pipeline/gpu_stage.h"
#include "gpu_grid.h"
#include "grid_options.h"

namespace rt {

// The grid as the pipeline's traversal: built over the uploaded scene each frame, walked per ray by grid.glsl.
class GridTraversal final : public gpu::Traversal {
public:
    explicit GridTraversal(GridOptions& options) : options_(options) {}

    void add_options(CLI::App& app) override { add_grid_options(app, options_); }
    void build(const gpu::FrameInputs& frame) override;
    std::string glsl() const override { return "03_uniform_grid/shaders/grid.glsl"; }   // the 3D-DDA, per ray
    gpu::ShaderDefines defines() const override { return {{"GRID_STATS", "1"}}; }
    void bind() const override;
    std::string steps() const override { return "grid cells"; }
    void report(gpu::FrameReport& report) override;   // grid_stats.h
    std::vector<std::string> programs() const override;

private:
    GridOptions& options_;                    // the stage's
    std::unique_ptr<GpuGrid> grid_;           // created with the first frame that needs it (needs the context)
    bool built_ = false;
    float lambda_used_ = kDefaultGridLambda;   // lambda after fitting the cells into the storage limit
};

// Stage 02's rasterized primary visibility (or, --primary trace, camera rays traced through the grid) + the grid.
class GridRenderer : public gpu::GpuStage {
public:
    GridRenderer();
    // Read by the primary visibility (--primary) and the traversal, which hold it by reference (set before a frame).
    GridOptions grid_options;
};

}  // namespace rt
