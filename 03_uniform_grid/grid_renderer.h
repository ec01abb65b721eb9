// Stage 03: the first acceleration structure, a uniform grid (uniform_grid.h explains it; gpu_grid.h builds it on
// the GPU every frame; shaders/grid.glsl walks it with the 3D-DDA). Everything else is stage 02's: the wavefront
// pipeline, the shading, and (with the default --primary raster) the G-buffer for primary rays, so 02 -> 03 changes
// only the traversal: brute force becomes the grid, and the image and every hit stay exactly the same.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "02_raster_hybrid/rasterized_primary_stage.h"
#include "gpu_grid.h"
#include "grid_options.h"

namespace rt {

class GridRenderer : public RasterizedPrimaryStage {
public:
    GridRenderer();
    ~GridRenderer() override;

    void add_options(CLI::App& app) override;   // the GPU options and grid_options.h's
    GridOptions grid_options;

protected:
    void build(const Scene& scene, const RenderSettings& settings) override;
    void render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) override;
    bool rasterizes_primary_rays() const override { return !grid_options.trace_primary; }
    std::vector<std::string> stage_programs() const override;
    void add_stage_stats(FrameResult& result) override;   // grid_stats.h

private:
    // Whether any ray of the frame is traced: traced primaries, shadows with lights, or reflections/refractions.
    static bool needs_grid(const Scene& scene, const RenderSettings& settings, bool trace_primary);
    void bind_grid() const;

    std::unique_ptr<GpuGrid> grid_;           // created with the first frame that needs it (needs the context)
    bool built_ = false;
    float lambda_used_ = kDefaultGridLambda;   // lambda after fitting the cells into the storage limit
};

}  // namespace rt
