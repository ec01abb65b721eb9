#version 450 core
// Hashing: one thread per ray, its 32-bit key (ray_sort.glsl: rs_ray_key; the mapping is in ray_keys.h).
#include "ray_sort.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RS_BINDING_0) readonly buffer Rays { RsRay rs_rays[]; };
layout(std430, binding = RS_BINDING_1) writeonly buffer Keys { uint rs_keys[]; };

uniform uint rs_first;   // rays[rs_first + i] gets key i
uniform uint rs_count;

void main() {
    const uint i = rt_global_index();
    if (i >= rs_count) return;
    rs_keys[i] = rs_ray_key(rs_rays[rs_first + i]);
}
