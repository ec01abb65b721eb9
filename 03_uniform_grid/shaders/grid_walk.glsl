// The 3D-DDA walk through the grid (Amanatides & Woo 1987), used by the traversal (grid.glsl) and tested on its own
// (walk_grid in uniform_grid.cpp is its C++ twin: the same cells and t-ranges, bit for bit). A walk is
//     GridWalk w;
//     if (grid_walk_begin(ray, w))
//         for (int i = 0; i < grid_walk_bound(); ++i) {
//             grid_walk_cell_end(ray, w);     // the current cell is w.cell, the ray is inside it for t in [w.t, w.t1]
//             ...
//             if (!grid_walk_next(w)) break;
//         }
#include "common/shaders/trace/camera.glsl"
#include "grid_common.glsl"

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
    w.t = abs(w.t);   // +0, not the -0 an origin on a boundary gives (t >= 0 here; as walk_grid)
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
    // BEGIN EXERCISE 03.dda_cell_end: per axis, the t where the ray crosses the current cell's next boundary
    // (grid_boundary; infinity on an axis the ray does not move along); the smallest names w.axis, and the cell ends
    // at w.t1 = that t, clamped to [w.t, w.t_exit].
    vec3 t_max;
    for (int a = 0; a < 3; ++a) {
        precise float tb = (grid_boundary(a, w.cell[a] + (w.step[a] > 0 ? 1 : 0)) - ray.origin[a]) / ray.direction[a];
        t_max[a] = w.step[a] == 0 ? RT_INFINITY : tb;
    }
    w.axis = t_max.x <= t_max.y ? (t_max.x <= t_max.z ? 0 : 2) : (t_max.y <= t_max.z ? 1 : 2);   // ties: x, y, z
    const float end = min(t_max[w.axis], w.t_exit);
    w.t1 = end > w.t ? end : w.t;   // not max(): it may return -0 for max(+0, -0), walk_grid gives +0
    // STUB: w.axis = 0;
    // STUB: w.t1 = w.t_exit;
    // END EXERCISE
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

