// Stage 03's traversal (Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing"): the ray walks
// the grid cell by cell, in order along the ray, and is tested only against the triangles listed in the cells it
// passes through. The wavefront pipeline (common/gpu/wavefront.h) calls trace_closest from its trace pass and
// trace_any from its shadow pass. Shader path: "03_uniform_grid/grid.glsl". C++ twin: walk_grid in uniform_grid.cpp.
#include "wavefront/wavefront.glsl"
#include "grid_common.glsl"


#ifdef GRID_STATS
// 64-bit counters (lo, hi) in grid_stats, as counters.glsl: per ray kind k (WF_KIND_*) rays [k], cells visited
// [4 + k], tests [8 + k]; [12] walks stopped by the loop bound (never, on a correct walk).
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
    grid_stat_add(4u + kind, cells);
    grid_stat_add(8u + kind, tests);
    if (bound_reached) grid_stat_add(12u, 1u);
}
#else
void grid_record(uint cells, uint tests, bool bound_reached) {}
#endif

bool grid_intersect(Ray ray, WatertightRay w, uint i, out float t, out float u, out float v) {
    vec3 a, b, c;
    grid_load_triangle(i, a, b, c);
#if RT_INTERSECT_METHOD == RT_INTERSECT_WATERTIGHT
    return intersect_watertight(ray, w, a, b, c, t, u, v);
#else
    return intersect_moller(ray, a, b, c, t, u, v);
#endif
}

// The walk's state: the current cell, the t-range [t, t1] the ray spends in it, and what is left of the grid box.
struct GridWalk {
    ivec3 cell, step;
    float t, t1, t_exit;
    int axis;   // the axis whose boundary ends the current cell
};

// Enters the grid box (slabs; an axis with d = 0 or -0 only checks the origin) and finds the start cell.
bool grid_walk_begin(Ray ray, out GridWalk w) {
    w.t = 0.0;
    w.t_exit = ray.tmax;
    w.step = ivec3(0);
    w.cell = ivec3(0);
    w.axis = 0;
    w.t1 = 0.0;
    for (int a = 0; a < 3; ++a) {
        const float b0 = grid_boundary(a, 0), b1 = grid_boundary(a, grid_res[a]);
        const float o = ray.origin[a], d = ray.direction[a];
        if (d == 0.0) {
            if (o < b0 || o > b1) return false;
            continue;
        }
        precise float t0 = (b0 - o) / d;
        precise float t1 = (b1 - o) / d;
        w.t = max(w.t, min(t0, t1));
        w.t_exit = min(w.t_exit, max(t0, t1));
    }
    if (!(w.t <= w.t_exit)) return false;
    for (int a = 0; a < 3; ++a) {
        precise float p = ray.origin[a] + w.t * ray.direction[a];
        w.cell[a] = grid_cell_of(a, p);
        w.step[a] = ray.direction[a] > 0.0 ? 1 : (ray.direction[a] < 0.0 ? -1 : 0);
    }
    return true;
}

// tMax per axis: the t of the next boundary (recomputed from the boundary rather than adding tDelta, so the walk
// agrees with the cells' own boundaries), then the end t1 of the current cell.
void grid_walk_cell_end(Ray ray, inout GridWalk w) {
    vec3 t_max;
    for (int a = 0; a < 3; ++a) {
        precise float tb = (grid_boundary(a, w.cell[a] + (w.step[a] > 0 ? 1 : 0)) - ray.origin[a]) / ray.direction[a];
        t_max[a] = w.step[a] == 0 ? RT_INFINITY : tb;
    }
    w.axis = t_max.x <= t_max.y ? (t_max.x <= t_max.z ? 0 : 2) : (t_max.y <= t_max.z ? 1 : 2);   // ties: x, y, z
    w.t1 = max(w.t, min(t_max[w.axis], w.t_exit));
}

// Steps into the next cell; false when the ray leaves the grid (or its t-range) there.
bool grid_walk_next(inout GridWalk w) {
    if (w.t1 >= w.t_exit) return false;
    w.cell[w.axis] += w.step[w.axis];
    if (w.cell[w.axis] < 0 || w.cell[w.axis] >= grid_res[w.axis]) return false;
    w.t = w.t1;
    return true;
}

// More steps than any walk takes (it crosses each boundary at most once): reaching it is a bug, counted in the stats.
int grid_walk_bound() { return grid_res.x + grid_res.y + grid_res.z + 3; }

// Closest hit, exactly brute force's: the smallest t, ties to the lowest triangle id. Triangles are tested cell by
// cell; a hit beyond the current cell's end may be beaten by one in a later cell, so the walk stops only when the best
// hit so far lies before the end of the current cell (every triangle that could hit closer or at the same t is
// listed in a cell already visited).
bool trace_closest(Ray ray, out Hit hit) {
    hit = no_hit();
    GridWalk w;
    uint cells = 0u, tests = 0u;
    bool bound_reached = false;
    if (grid_walk_begin(ray, w)) {
        const WatertightRay wr = watertight_ray(ray.direction);
        const int bound = grid_walk_bound();
        int i = 0;
        for (; i < bound; ++i) {
            grid_walk_cell_end(ray, w);
            ++cells;
            const uvec2 range = grid_cell_range(grid_cell_index(w.cell));
            tests += range.y - range.x;
            for (uint k = range.x; k < range.y; ++k) {
                const uint tri = grid_triangle(k);
                float t, u, v;
                if (grid_intersect(ray, wr, tri, t, u, v) &&
                    (t < hit.t || (t == hit.t && int(tri) < hit.triangle))) {
                    hit.t = t;
                    hit.u = u;
                    hit.v = v;
                    hit.triangle = int(tri);
                }
            }
            if (hit.triangle >= 0 && hit.t < w.t1) break;
            if (!grid_walk_next(w)) break;
        }
        bound_reached = i == bound;
    }
    wf_count_tests(tests);
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
    grid_record(cells, tests, bound_reached);
    return found;
}
