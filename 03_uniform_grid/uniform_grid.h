// Stage 03's acceleration structure on the CPU: a uniform grid, short and readable. It is the reference the GPU build
// (grid_renderer.cpp, shaders/grid_*.comp) is tested against, cell by cell, and the place to read the ideas first:
//
//   1. Resolution (choose_resolution): about lambda x N cells for N triangles, shaped like the scene box so cells
//      are near cubes (Wald et al. 2006; Ize et al. 2006): k = cbrt(lambda N / V), res_a = ceil(extent_a k).
//   2. Build (build_grid): each triangle is listed in every cell its triangle/box overlap test accepts (Akenine-
//      Moller's separating axes, on cells enlarged by a small margin so a touching triangle is never left out), in
//      increasing triangle id. The GPU does the same with count -> scan -> write pairs -> radix sort -> cell ranges.
//   3. Traversal (walk_grid): Amanatides & Woo's 3D-DDA visits the cells a ray passes through, in order, each with
//      the t-range the ray spends inside it.
//
// All float arithmetic here is written in the same order as its GLSL twin (shaders/grid_common.glsl), so both sides
// list exactly the same triangles per cell.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "common/scene/scene.h"
#include "common/trace/intersect.h"
#include "common/trace/ray.h"

namespace rt {

// The grid's geometry (std430 mirror of GridInfo in shaders/grid_common.glsl).
struct GridParams {
    glm::vec3 lo{0.0f};      float margin = 0.0f;   // lo: the grid's min corner; margin: cells grow by it in the
    glm::vec3 cell{1.0f};    std::uint32_t cell_count = 1;   // overlap test (conservative)
    glm::ivec3 res{1};       std::uint32_t triangle_count = 0;
};
static_assert(sizeof(GridParams) == 48);

constexpr float kDefaultGridLambda = 4.0f;
constexpr int kMaxGridResPerAxis = 1024;

// Cells per axis for n triangles in `bounds` (see above); each axis in [1, kMaxGridResPerAxis].
glm::ivec3 choose_resolution(const Bounds& bounds, std::size_t n, float lambda);
// The grid over `bounds` (padded a little, so no triangle lies on its outer faces) at resolution `res`.
GridParams make_grid_params(const Bounds& bounds, glm::ivec3 res, std::size_t triangle_count);

// Cell (x, y, z) is number x + res.x (y + res.y z) (GLSL: grid_cell_index).
std::size_t grid_cell_index(const GridParams& g, glm::ivec3 cell);
// The coordinate of the boundary between cells n - 1 and n on axis a (GLSL: grid_boundary).
float grid_boundary(const GridParams& g, int a, int n);
// Akenine-Moller's triangle/box overlap (13 separating axes), conservative: touching counts as overlapping.
bool triangle_box_overlap(glm::vec3 center, glm::vec3 half, glm::vec3 a, glm::vec3 b, glm::vec3 c);
// The cells (x, y, z ranges, inclusive) of the triangle's bounding box, and whether cell (x, y, z) overlaps it.
void triangle_cell_range(const GridParams& g, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::ivec3& first,
                         glm::ivec3& last);
bool triangle_overlaps_cell(const GridParams& g, glm::ivec3 cell, glm::vec3 a, glm::vec3 b, glm::vec3 c);

struct CpuGrid {
    GridParams params;
    std::vector<std::vector<std::uint32_t>> cells;   // triangle ids per cell, increasing (index: grid_cell_index)
    std::size_t pairs() const;
    const std::vector<std::uint32_t>& at(glm::ivec3 cell) const;
};
CpuGrid build_grid(const Scene& scene, glm::ivec3 res);

// One step of the DDA: the cell and the t-range [t0, t1] the ray spends in it.
struct GridStep {
    glm::ivec3 cell;
    float t0, t1;
};
// Visits the cells the ray o + t d, 0 <= t < tmax, passes through, in order, until visit returns false. Returns the
// number of cells visited; `hit_bound` is set when the loop bound (res.x + res.y + res.z + 3 steps, more than any
// walk needs) stopped it, which never happens on a correct walk.
int walk_grid(const GridParams& g, glm::vec3 o, glm::vec3 d, float tmax,
              const std::function<bool(const GridStep&)>& visit, bool* hit_bound = nullptr);

// Closest hit through the grid, exactly brute force's (BruteForceTracer::closest: triangles in id order, each one
// tested against the tmax the previous hits left). Two phases:
//   1. Walk: test each visited cell's triangles with the ray's own tmax, keep the smallest t (ties: lowest id), and
//      stop once that t lies before the current cell's end by a relative kGridTieRange (every triangle that could
//      hit at that t or before lies in a visited cell).
//   2. Near ties: brute force keeps a hit only when strictly closer, so at an exactly equal t the lowest id wins
//      whatever the order, as in phase 1. But when another triangle hit at a different t within kGridTieRange of
//      the best, brute force's answer depends on its test order: the watertight test compares t with tmax in scaled
//      form (T < tmax * det) before dividing, so of two hits an ulp apart the later-tested, closer one may be
//      rejected against the earlier one's tmax. Those triangles are tested again as brute force does: in increasing
//      id, each against the tmax the last hit left. (Exact ties alone, as on a quad's shared diagonal, skip this.)
//      They lie in the last few cells visited (a ring of kGridTieCells); when the tie range reaches further back,
//      every triangle is tested (never seen in practice, but never wrong).
// grid.glsl's trace_closest is its GLSL twin.
constexpr float kGridTieRange = 1e-5f;
constexpr int kGridTieCells = 8;
struct GridTraceCount {
    int cells = 0;
    std::size_t tests = 0;
    bool bound_reached = false;
};
// With `cutouts` (a scene with MASK or BLEND materials), a hit where the surface is transparent is no hit
// (common/trace/opacity.h), in both phases; the result is brute force's with the same test (`blend_coverage`: BLEND
// surfaces are hit wherever they cover anything, Effects::blend).
Hit<float> grid_closest_hit(const CpuGrid& grid, const std::vector<glm::vec3>& positions, const Ray<float>& ray,
                            IntersectMethod method, GridTraceCount* count = nullptr, const Scene* cutouts = nullptr,
                            bool blend_coverage = false);

}  // namespace rt
