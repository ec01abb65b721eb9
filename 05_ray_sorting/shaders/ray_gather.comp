#version 450 core
// After sorting: copies the batch's rays into sorted order, sorted[i] = rays[order[i]], so the stage-04 hierarchy is
// built over neighbours that share a key.
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_STAGE_BINDING_0) readonly buffer Rays { RsRay rs_rays[]; };
layout(std430, binding = RS_STAGE_BINDING_1) readonly buffer Order { uint rs_order[]; };
layout(std430, binding = RS_STAGE_BINDING_2) writeonly buffer Sorted { RsRay rs_sorted[]; };

uniform uint rs_count;

void main() {
    const uint i = rt_global_index();
    if (i >= rs_count) return;
    rs_sorted[i] = rs_rays[rs_order[i]];
}
