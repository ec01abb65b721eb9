#include "uniform_grid.h"

#include <algorithm>
#include <cmath>

#include "common/trace/opacity.h"

namespace rt {

glm::ivec3 choose_resolution(const Bounds& bounds, std::size_t n, float lambda) {
    if (n == 0 || bounds.empty()) return glm::ivec3(1);
    const glm::vec3 extent = bounds.hi - bounds.lo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    if (!(longest > 0.0f)) return glm::ivec3(1);
    // A flat axis (a single quad) gets one cell; its volume is taken as 1/1000 of the longest side so k stays finite.
    const glm::vec3 e = glm::max(extent, glm::vec3(longest * 1e-3f));
    const double k = std::cbrt(double(lambda) * double(n) / (double(e.x) * e.y * e.z));   // cells per unit length
    glm::ivec3 res;
    for (int a = 0; a < 3; ++a)
        res[a] = int(std::clamp(std::ceil(double(extent[a]) * k), 1.0, double(kMaxGridResPerAxis)));
    return res;
}

GridParams make_grid_params(const Bounds& bounds, glm::ivec3 res, std::size_t triangle_count) {
    GridParams g;
    g.res = res;
    g.cell_count = std::uint32_t(res.x) * std::uint32_t(res.y) * std::uint32_t(res.z);
    g.triangle_count = std::uint32_t(triangle_count);
    if (bounds.empty()) return g;   // no triangles: one unit cell at the origin, listing nothing
    const glm::vec3 extent = bounds.hi - bounds.lo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    const float far = std::max(glm::length(bounds.lo), glm::length(bounds.hi));   // distance from the origin
    // Padding keeps every triangle strictly inside the grid box; the margin absorbs float rounding of hit points
    // and cell boundaries (both grow with the scene's size and its distance from the origin).
    const float pad = 1e-4f * longest + 1e-6f * far + 1e-30f;
    g.lo = bounds.lo - glm::vec3(pad);
    g.cell = (bounds.hi + glm::vec3(pad) - g.lo) / glm::vec3(res);
    g.margin = 1e-4f * std::min({g.cell.x, g.cell.y, g.cell.z}) + 1e-6f * far;
    return g;
}

std::size_t grid_cell_index(const GridParams& g, glm::ivec3 c) {
    return std::size_t(c.x) + std::size_t(g.res.x) * (std::size_t(c.y) + std::size_t(g.res.y) * std::size_t(c.z));
}

float grid_boundary(const GridParams& g, int a, int n) { return g.lo[a] + float(n) * g.cell[a]; }

namespace {

glm::vec3 cross3(glm::vec3 a, glm::vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float dot3(glm::vec3 a, glm::vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Is `axis` a separating axis of the triangle (v0, v1, v2) and the box [-half, half]? Strict: touching is overlap.
bool separated(glm::vec3 axis, glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, glm::vec3 half) {
    const float p0 = dot3(axis, v0), p1 = dot3(axis, v1), p2 = dot3(axis, v2);
    const float r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangle_box_overlap(glm::vec3 center, glm::vec3 half, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 v0 = a - center, v1 = b - center, v2 = c - center;
    // 1. The box's face normals: the triangle's bounding box against the box.
    for (int i = 0; i < 3; ++i)
        if (std::min({v0[i], v1[i], v2[i]}) > half[i] || std::max({v0[i], v1[i], v2[i]}) < -half[i]) return false;
    // 2. The triangle's normal: the plane against the box.
    const glm::vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    if (separated(cross3(e0, e1), v0, v1, v2, half)) return false;
    // 3. The nine cross products of a box axis and a triangle edge.
    const glm::vec3 edges[3] = {e0, e1, e2};
    for (int i = 0; i < 3; ++i) {
        glm::vec3 u(0.0f);
        u[i] = 1.0f;
        for (const glm::vec3& e : edges)
            if (separated(cross3(u, e), v0, v1, v2, half)) return false;
    }
    return true;
}

namespace {
int cell_of(const GridParams& g, int a, float x) {
    const float f = std::floor((x - g.lo[a]) / g.cell[a]);
    return int(std::clamp(f, 0.0f, float(g.res[a] - 1)));
}
}  // namespace

void triangle_cell_range(const GridParams& g, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::ivec3& first,
                         glm::ivec3& last) {
    const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    for (int i = 0; i < 3; ++i) {
        first[i] = cell_of(g, i, lo[i] - g.margin);
        last[i] = cell_of(g, i, hi[i] + g.margin);
    }
}

bool triangle_overlaps_cell(const GridParams& g, glm::ivec3 cell, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    glm::vec3 center, half;
    for (int i = 0; i < 3; ++i) {
        const float lo = grid_boundary(g, i, cell[i]), hi = grid_boundary(g, i, cell[i] + 1);
        center[i] = (lo + hi) * 0.5f;
        half[i] = (hi - lo) * 0.5f + g.margin;   // the cell, grown by the margin: conservative
    }
    return triangle_box_overlap(center, half, a, b, c);
}

const std::vector<std::uint32_t>& CpuGrid::at(glm::ivec3 cell) const { return cells[grid_cell_index(params, cell)]; }

std::size_t CpuGrid::pairs() const {
    std::size_t n = 0;
    for (const auto& c : cells) n += c.size();
    return n;
}

CpuGrid build_grid(const Scene& scene, glm::ivec3 res) {
    CpuGrid grid;
    grid.params = make_grid_params(scene.bounds, res, scene.triangle_count());
    const GridParams& g = grid.params;
    grid.cells.resize(g.cell_count);
    for (std::uint32_t t = 0; t < g.triangle_count; ++t) {   // increasing id: each cell's list comes out sorted
        const glm::vec3 a = scene.positions[3 * t], b = scene.positions[3 * t + 1], c = scene.positions[3 * t + 2];
        glm::ivec3 first, last;
        triangle_cell_range(g, a, b, c, first, last);
        // BEGIN EXERCISE 03.grid_cells: the C++ twin of grid_build.glsl's cell walk (GpuGrid.* compares the two
        // grids cell by cell): every cell of [first, last] (x fastest, then y, then z) the triangle overlaps
        // (triangle_overlaps_cell) lists t.
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x)
                    if (triangle_overlaps_cell(g, {x, y, z}, a, b, c))
                        grid.cells[grid_cell_index(g, {x, y, z})].push_back(t);
        // STUB: (void)a, (void)b, (void)c;
        // END EXERCISE
    }
    return grid;
}

int walk_grid(const GridParams& g, glm::vec3 o, glm::vec3 d, float tmax,
              const std::function<bool(const GridStep&)>& visit, bool* hit_bound) {
    if (hit_bound) *hit_bound = false;
    // Entry and exit of the grid box (slabs). An axis the ray does not move along (d = 0 or -0) only checks that
    // the origin lies within the slab.
    float t_enter = 0.0f, t_exit = tmax;
    for (int a = 0; a < 3; ++a) {
        const float b0 = grid_boundary(g, a, 0), b1 = grid_boundary(g, a, g.res[a]);
        if (d[a] == 0.0f) {
            if (o[a] < b0 || o[a] > b1) return 0;
            continue;
        }
        float t0 = (b0 - o[a]) / d[a], t1 = (b1 - o[a]) / d[a];
        if (t0 > t1) std::swap(t0, t1);
        t_enter = std::max(t_enter, t0);
        t_exit = std::min(t_exit, t1);
    }
    if (!(t_enter <= t_exit)) return 0;
    t_enter = std::abs(t_enter);   // +0, not the -0 an origin on a boundary may give (t_enter >= 0 here)
    // The start cell: where the ray enters (clamped: rounding may put the entry point just outside).
    glm::ivec3 cell, step;
    for (int a = 0; a < 3; ++a) {
        cell[a] = cell_of(g, a, o[a] + t_enter * d[a]);
        step[a] = d[a] > 0.0f ? 1 : (d[a] < 0.0f ? -1 : 0);
    }
    // tMax[a]: the t where the ray crosses the next boundary on axis a. Amanatides & Woo add tDelta = cell / |d|
    // per step; here it is recomputed from the boundary itself, which is the same value without accumulated
    // rounding, so the walk agrees with the cells' own boundaries (grid_boundary) exactly.
    const int bound = g.res.x + g.res.y + g.res.z + 3;
    float t = t_enter;
    int visited = 0;
    for (int i = 0; i < bound; ++i) {
        int axis;
        float t1;
        // BEGIN EXERCISE 03.dda_cell_end: the C++ twin of grid_walk.glsl's grid_walk_cell_end (the CPU hard cases
        // grade this one, the GLSL hard cases compare the two): per axis the t of the next boundary (grid_boundary;
        // infinity where step is 0); the smallest names axis (ties: x, then y, then z), and the cell ends at t1 =
        // that t, clamped to [t, t_exit].
        glm::vec3 t_max;
        for (int a = 0; a < 3; ++a)
            t_max[a] = step[a] == 0 ? std::numeric_limits<float>::infinity()
                                    : (grid_boundary(g, a, cell[a] + (step[a] > 0 ? 1 : 0)) - o[a]) / d[a];
        axis = t_max.x <= t_max.y ? (t_max.x <= t_max.z ? 0 : 2) : (t_max.y <= t_max.z ? 1 : 2);
        const float end = std::min(t_max[axis], t_exit);
        t1 = end > t ? end : t;   // the cell ends no earlier than it starts
        // STUB: axis = 0;
        // STUB: t1 = t_exit;
        // END EXERCISE
        ++visited;
        if (!visit({cell, t, t1}) || t1 >= t_exit) return visited;
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= g.res[axis]) return visited;
        t = t1;
    }
    if (hit_bound) *hit_bound = true;
    return visited;
}

namespace {

struct TriangleTest {
    const std::vector<glm::vec3>& positions;
    IntersectMethod method;
    WatertightRay<float> w;
    const Scene* cutouts = nullptr;   // a transparent hit is no hit (opacity.h)
    bool blend_coverage = false;      // BLEND surfaces are hit wherever they cover anything
    std::size_t tests = 0;
    bool operator()(const Ray<float>& ray, std::uint32_t t, float& th, float& u, float& v) {
        ++tests;
        const glm::vec3 &a = positions[3 * t], &b = positions[3 * t + 1], &c = positions[3 * t + 2];
        const bool hit = method == IntersectMethod::Watertight ? intersect_watertight(ray, w, a, b, c, th, u, v)
                                                               : intersect_moller(ray, a, b, c, th, u, v);
        return hit && (!cutouts || surface_opaque(*cutouts, t, u, v, blend_coverage));
    }
};

// Brute force's fold over some triangles, in increasing id: each hit shrinks tmax for the next, and replaces the
// kept one only when strictly closer (BruteForceTracer::record).
void fold_hit(TriangleTest& test, Ray<float>& ray, std::uint32_t t, Hit<float>& hit) {
    float th, u, v;
    if (test(ray, t, th, u, v) && th < hit.t) {
        hit = {th, u, v, std::int32_t(t)};
        ray.tmax = th;
    }
}

}  // namespace

Hit<float> grid_closest_hit(const CpuGrid& grid, const std::vector<glm::vec3>& positions, const Ray<float>& ray,
                            IntersectMethod method, GridTraceCount* count, const Scene* cutouts,
                            bool blend_coverage) {
    const GridParams& g = grid.params;
    TriangleTest test{positions, method, WatertightRay<float>(ray.direction), cutouts, blend_coverage};
    Hit<float> best;
    float second = std::numeric_limits<float>::infinity();   // the smallest t of another triangle, > best.t
    GridStep ring[kGridTieCells];                             // the last cells visited
    int visited = 0;
    bool bound = false;
    // Phase 1: the walk.
    walk_grid(g, ray.origin, ray.direction, ray.tmax, [&](const GridStep& step) {
        ring[visited++ % kGridTieCells] = step;
        for (std::uint32_t t : grid.at(step.cell)) {
            float th, u, v;
            if (!test(ray, t, th, u, v) || std::int32_t(t) == best.triangle) continue;
            if (th < best.t || (th == best.t && std::int32_t(t) < best.triangle)) {
                if (th < best.t) second = std::min(second, best.t);   // an exact tie is no near tie (see the .h)
                best = {th, u, v, std::int32_t(t)};
            } else if (th > best.t) {
                second = std::min(second, th);
            }
        }
        return !(best.valid() && best.t * (1.0f + kGridTieRange) < step.t1);
    }, &bound);
    // Phase 2: near ties, in brute force's order.
    if (best.valid() && second <= best.t * (1.0f + kGridTieRange)) {
        const float lo = best.t * (1.0f - kGridTieRange), hi = best.t * (1.0f + kGridTieRange);
        const int kept = std::min(visited, kGridTieCells);
        std::vector<const std::vector<std::uint32_t>*> lists;
        for (int i = 0; i < kept; ++i) {
            const GridStep& s = ring[(visited - kept + i) % kGridTieCells];
            if (s.t1 >= lo && s.t0 <= hi)
                lists.push_back(&grid.at(s.cell));
        }
        Ray<float> r = ray;
        best = Hit<float>();
        if (visited > kGridTieCells && ring[visited % kGridTieCells].t0 > lo) {
            // The tie range reaches back beyond the ring: every triangle, as brute force.
            for (std::uint32_t t = 0; t < g.triangle_count; ++t) fold_hit(test, r, t, best);
        } else {
            // Merge the cells' sorted lists: each triangle once, in increasing id.
            std::vector<std::size_t> cursor(lists.size(), 0);
            for (std::int64_t last = -1;;) {
                std::uint32_t next = std::numeric_limits<std::uint32_t>::max();
                for (std::size_t c = 0; c < lists.size(); ++c) {
                    while (cursor[c] < lists[c]->size() && std::int64_t((*lists[c])[cursor[c]]) <= last) ++cursor[c];
                    if (cursor[c] < lists[c]->size()) next = std::min(next, (*lists[c])[cursor[c]]);
                }
                if (next == std::numeric_limits<std::uint32_t>::max()) break;
                fold_hit(test, r, next, best);
                last = next;
            }
        }
    }
    if (count) *count = {visited, test.tests, bound};
    return best;
}

}  // namespace rt
