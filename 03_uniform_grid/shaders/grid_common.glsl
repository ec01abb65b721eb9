// The uniform grid on the GPU: its geometry, the triangle/cell overlap test of the build, and the buffers the
// traversal reads. GLSL twin of uniform_grid.{h,cpp}, operation for operation (`precise`: no FMA contraction), so
// the GPU lists exactly the triangles the CPU grid lists in each cell.
//
// The grid is one shader storage buffer (a traversal may add only a block or two: the pipeline's passes already use
// most of the 16 a shader may have), bound at 24, the first binding the wavefront pipeline leaves to a traversal:
//   header      the geometry (GridParams in uniform_grid.h), then 32 uints of the traversal's counters (GRID_STATS)
//   grid_data   per cell c: [begin, end) at 2c, 2c + 1, indices into the triangle lists that follow the ranges, at
//               2 * grid_cell_count: triangle ids, cell after cell, increasing within a cell (the sorted pairs)
// The build passes (grid_build.glsl) use bindings 27..30: per-chunk counts/offsets, per-triangle counts/offsets, the
// pair keys (cells) and pair values (triangles).
#include "common/shaders/bindings.glsl"

#define GRID_BINDING 24
#define GRID_BINDING_CHUNKS 27
#define GRID_BINDING_OFFSETS 28
#define GRID_BINDING_KEYS 29
#define GRID_BINDING_VALUES 30
#define GRID_STAT_COUNT 32u

layout(std430, binding = GRID_BINDING) buffer Grid {
    vec3 grid_lo; float grid_margin;
    vec3 grid_cell; uint grid_cell_count;
    ivec3 grid_res; uint grid_triangle_count;
    uint grid_stats[GRID_STAT_COUNT];
    uint grid_data[];
};

// The scene's vertex positions (scene.glsl's rt_positions, the same buffer): the grid's passes read nothing else of
// the scene, and declaring only this block keeps the trace and shadow passes within the 16 blocks a shader may use.
layout(std430, binding = RT_BINDING_POSITIONS) readonly buffer GridPositions { vec4 grid_positions[]; };
void grid_load_triangle(uint t, out vec3 a, out vec3 b, out vec3 c) {
    a = grid_positions[3u * t].xyz;
    b = grid_positions[3u * t + 1u].xyz;
    c = grid_positions[3u * t + 2u].xyz;
}

uvec2 grid_cell_range(uint cell) { return uvec2(grid_data[2u * cell], grid_data[2u * cell + 1u]); }
uint grid_triangle(uint k) { return grid_data[2u * grid_cell_count + k]; }

float grid_boundary(int a, int n) {
    precise float b = grid_lo[a] + float(n) * grid_cell[a];
    return b;
}

int grid_cell_of(int a, float x) {
    precise float f = floor((x - grid_lo[a]) / grid_cell[a]);
    return int(clamp(f, 0.0, float(grid_res[a] - 1)));
}

uint grid_cell_index(ivec3 c) { return uint(c.x) + uint(grid_res.x) * (uint(c.y) + uint(grid_res.y) * uint(c.z)); }

vec3 grid_cross(vec3 a, vec3 b) {
    precise vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
    return c;
}
float grid_dot(vec3 a, vec3 b) {
    precise float d = a.x * b.x + a.y * b.y + a.z * b.z;
    return d;
}

bool grid_separated(vec3 axis, vec3 v0, vec3 v1, vec3 v2, vec3 half_size) {
    const float p0 = grid_dot(axis, v0), p1 = grid_dot(axis, v1), p2 = grid_dot(axis, v2);
    precise float r = half_size.x * abs(axis.x) + half_size.y * abs(axis.y) + half_size.z * abs(axis.z);
    return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

// Akenine-Moller's triangle/box overlap (13 separating axes); touching counts as overlapping.
bool grid_triangle_box_overlap(vec3 center, vec3 half_size, vec3 a, vec3 b, vec3 c) {
    precise vec3 v0 = a - center;
    precise vec3 v1 = b - center;
    precise vec3 v2 = c - center;
    for (int i = 0; i < 3; ++i)
        if (min(v0[i], min(v1[i], v2[i])) > half_size[i] || max(v0[i], max(v1[i], v2[i])) < -half_size[i])
            return false;
    precise vec3 e0 = v1 - v0;
    precise vec3 e1 = v2 - v1;
    precise vec3 e2 = v0 - v2;
    if (grid_separated(grid_cross(e0, e1), v0, v1, v2, half_size)) return false;
    for (int i = 0; i < 3; ++i) {
        vec3 u = vec3(0.0);
        u[i] = 1.0;
        if (grid_separated(grid_cross(u, e0), v0, v1, v2, half_size)) return false;
        if (grid_separated(grid_cross(u, e1), v0, v1, v2, half_size)) return false;
        if (grid_separated(grid_cross(u, e2), v0, v1, v2, half_size)) return false;
    }
    return true;
}

void grid_triangle_cell_range(vec3 a, vec3 b, vec3 c, out ivec3 first, out ivec3 last) {
    const vec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
    for (int i = 0; i < 3; ++i) {
        precise float l = lo[i] - grid_margin;
        precise float h = hi[i] + grid_margin;
        first[i] = grid_cell_of(i, l);
        last[i] = grid_cell_of(i, h);
    }
}

bool grid_triangle_overlaps_cell(ivec3 cell, vec3 a, vec3 b, vec3 c) {
    vec3 center, half_size;
    for (int i = 0; i < 3; ++i) {
        const float lo = grid_boundary(i, cell[i]), hi = grid_boundary(i, cell[i] + 1);
        precise float m = (lo + hi) * 0.5;
        precise float h = (hi - lo) * 0.5 + grid_margin;
        center[i] = m;
        half_size[i] = h;
    }
    return grid_triangle_box_overlap(center, half_size, a, b, c);
}
