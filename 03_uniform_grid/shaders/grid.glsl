// Stage 03's traversal (Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing"): the ray walks
// the grid cell by cell, in order along the ray, and is tested only against the triangles listed in the cells it
// passes through. The wavefront pipeline (common/gpu/pipeline/wavefront.h) calls trace_closest from its trace pass and
// trace_any from its shadow pass. Shader path: "03_uniform_grid/shaders/grid.glsl". C++ twin: walk_grid in uniform_grid.cpp.
#include "common/shaders/wavefront/wavefront.glsl"
#include "grid_walk.glsl"
#include "common/shaders/trace/opacity.glsl"


#if defined(GRID_STATS) && defined(COUNT_TESTS)   // compiled out without test counting (timing runs)
// 64-bit counters (lo, hi) in grid_stats, as counters.glsl: per ray kind k (WF_KIND_*, five kinds) rays [k], cells
// visited [5 + k], tests [10 + k]; [15] walks stopped by the loop bound (never, on a correct walk).
void grid_stat_add(uint index, uint value) {
    if (value == 0u) return;
    const uint old = atomicAdd(grid_stats[2u * index], value);
    if (old + value < old) atomicAdd(grid_stats[2u * index + 1u], 1u);
}
// The kind of the ray this thread traces: the trace and shadow passes run one thread per ray of wf_rays_in, in work
// groups of 64 (their local_size_x; gl_WorkGroupSize cannot be used here, before the pass declares it).
void grid_record(uint cells, uint tests, bool bound_reached) {
    const uint ray = rt_group_index() * 64u + gl_LocalInvocationIndex;
    const uint kind = wf_kind(wf_rays_in[wf_input_first + ray]);
    grid_stat_add(kind, 1u);
    grid_stat_add(5u + kind, cells);
    grid_stat_add(10u + kind, tests);
    if (bound_reached) grid_stat_add(15u, 1u);
}
#else
void grid_record(uint cells, uint tests, bool bound_reached) {}
#endif

bool grid_intersect(Ray ray, WatertightRay w, uint i, out float t, out float u, out float v) {
    vec3 a, b, c;
    grid_load_triangle(i, a, b, c);
#if RT_INTERSECT_METHOD == RT_INTERSECT_WATERTIGHT
    const bool hit = intersect_watertight(ray, w, a, b, c, t, u, v);
#else
    const bool hit = intersect_moller(ray, a, b, c, t, u, v);
#endif
    return hit && cutout_opaque(i, u, v);   // a transparent hit is no hit (opacity.glsl): both phases stay exact
}

// Closest hit, exactly brute force's (02_raster_hybrid/shaders/brute_force.glsl: triangles in id order, each hit shrinking tmax for
// the next). grid_closest_hit in uniform_grid.cpp is the C++ twin and explains the two phases:
//   1. the walk tests each visited cell's triangles with the ray's own tmax and keeps the smallest t (ties: lowest
//      id); a hit may lie beyond the current cell (its triangle spans cells) where a closer one may wait, so the walk
//      stops only once the best t lies before the current cell's end (by a relative GRID_TIE_RANGE);
//   2. an exactly equal t goes to the lowest id in any order (a hit replaces the kept one only when strictly
//      closer), but when another triangle hit at a different t within GRID_TIE_RANGE of the best, the order of the
//      tests decides between them (the watertight test compares t with tmax in scaled form, before dividing, so a
//      closer hit an ulp away may fail against the tmax an earlier one left): those cells' triangles are tested
//      again in brute force's order, increasing id, merging the sorted lists of the last few cells visited.
#define GRID_TIE_RANGE 1e-5
#define GRID_TIE_CELLS 8

void grid_fold_hit(inout Ray ray, WatertightRay wr, uint tri, inout Hit hit) {
    float t, u, v;
    if (grid_intersect(ray, wr, tri, t, u, v) && t < hit.t) {
        ray.tmax = t;
        hit.t = t;
        hit.u = u;
        hit.v = v;
        hit.triangle = int(tri);
    }
}

bool trace_closest(Ray ray, out Hit hit) {
    hit = no_hit();
    GridWalk w;
    uint cells = 0u, tests = 0u;
    bool bound_reached = false;
    float second = RT_INFINITY;   // the smallest t of another triangle, > hit.t (exact ties need no phase 2)
    uint ring_cell[GRID_TIE_CELLS];
    float ring_t0[GRID_TIE_CELLS], ring_t1[GRID_TIE_CELLS];
    const WatertightRay wr = watertight_ray(ray.direction);
    // Phase 1: the walk.
    if (grid_walk_begin(ray, w)) {
        const int bound = grid_walk_bound();
        int i = 0;
        for (; i < bound; ++i) {
            grid_walk_cell_end(ray, w);
            const uint cell = grid_cell_index(w.cell);
            ring_cell[cells % GRID_TIE_CELLS] = cell;
            ring_t0[cells % GRID_TIE_CELLS] = w.t;
            ring_t1[cells % GRID_TIE_CELLS] = w.t1;
            ++cells;
            const uvec2 range = grid_cell_range(cell);
            tests += range.y - range.x;
            for (uint k = range.x; k < range.y; ++k) {
                const uint tri = grid_triangle(k);
                float t, u, v;
                if (!grid_intersect(ray, wr, tri, t, u, v) || int(tri) == hit.triangle) continue;
                if (t < hit.t || (t == hit.t && int(tri) < hit.triangle)) {
                    if (t < hit.t) second = min(second, hit.t);
                    hit.t = t;
                    hit.u = u;
                    hit.v = v;
                    hit.triangle = int(tri);
                } else if (t > hit.t) {
                    second = min(second, t);
                }
            }
            precise float reach = hit.t * (1.0 + GRID_TIE_RANGE);
            if (hit.triangle >= 0 && reach < w.t1) break;
            if (!grid_walk_next(w)) break;
        }
        bound_reached = i == bound;
    }
    // Phase 2: near ties, in brute force's order.
    precise float hi = hit.t * (1.0 + GRID_TIE_RANGE);
    if (hit.triangle >= 0 && second <= hi) {
        precise float lo = hit.t * (1.0 - GRID_TIE_RANGE);
        const uint kept = min(cells, uint(GRID_TIE_CELLS));
        const uint oldest = (cells - kept) % uint(GRID_TIE_CELLS);
        Ray r = ray;
        hit = no_hit();
        if (cells > uint(GRID_TIE_CELLS) && ring_t0[oldest] > lo) {
            for (uint t = 0u; t < grid_triangle_count; ++t) grid_fold_hit(r, wr, t, hit);   // ties reach further back
            tests += grid_triangle_count;
        } else {
            uint cursor[GRID_TIE_CELLS], end[GRID_TIE_CELLS];
            for (uint i = 0u; i < kept; ++i) {
                const uint e = (oldest + i) % uint(GRID_TIE_CELLS);
                const uvec2 range = grid_cell_range(ring_cell[e]);
                const bool near = ring_t1[e] >= lo && ring_t0[e] <= hi;
                cursor[i] = range.x;
                end[i] = near ? range.y : range.x;
            }
            // Merge the cells' sorted lists: each triangle once, in increasing id.
            for (int last = -1;;) {
                uint next = 0xffffffffu;
                for (uint i = 0u; i < kept; ++i) {
                    while (cursor[i] < end[i] && int(grid_triangle(cursor[i])) <= last) ++cursor[i];
                    if (cursor[i] < end[i]) next = min(next, grid_triangle(cursor[i]));
                }
                if (next == 0xffffffffu) break;
                grid_fold_hit(r, wr, next, hit);
                ++tests;
                last = int(next);
            }
        }
    }
    wf_count_tests(tests);
    wf_count_steps(cells);   // --pixel: the cells this ray walked
    grid_record(cells, tests, bound_reached);
    return hit.triangle >= 0;
}

// Any hit (shadow rays): the first triangle hit with 0 < t < tmax in any visited cell blocks the light.
bool trace_any(Ray ray) {
    GridWalk w;
    uint cells = 0u, tests = 0u;
    bool found = false, bound_reached = false;
    if (grid_walk_begin(ray, w)) {
        const WatertightRay wr = watertight_ray(ray.direction);
        const int bound = grid_walk_bound();
        int i = 0;
        for (; i < bound && !found; ++i) {
            grid_walk_cell_end(ray, w);
            ++cells;
            const uvec2 range = grid_cell_range(grid_cell_index(w.cell));
            for (uint k = range.x; k < range.y && !found; ++k) {
                float t, u, v;
                ++tests;
                found = grid_intersect(ray, wr, grid_triangle(k), t, u, v);
            }
            if (!found && !grid_walk_next(w)) break;
        }
        bound_reached = !found && i == bound;
    }
    wf_count_tests(tests);
    wf_count_steps(cells);   // --pixel: the cells this ray walked
    grid_record(cells, tests, bound_reached);
    return found;
}
