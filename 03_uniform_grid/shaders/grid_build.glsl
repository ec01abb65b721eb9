// Shared by the build passes: one thread per triangle walks the cells of its bounding box and calls
// grid_visit_cell(cell index, k) for the k-th cell it overlaps (grid_count.comp counts, grid_write.comp writes).
#include "grid_common.glsl"
#include "compute.glsl"

layout(local_size_x = 64) in;

void grid_visit_cell(uint triangle, uint cell, uint k);

// Returns how many cells triangle t overlaps.
uint grid_for_each_cell(uint t) {
    vec3 a, b, c;
    grid_load_triangle(t, a, b, c);
    ivec3 first, last;
    grid_triangle_cell_range(a, b, c, first, last);
    uint k = 0u;
    for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x)
                if (grid_triangle_overlaps_cell(ivec3(x, y, z), a, b, c))
                    grid_visit_cell(t, grid_cell_index(ivec3(x, y, z)), k++);
    return k;
}
