#version 450 core
// The per-frame geometry input of stage 04. One thread per triangle writes its bounding sphere (with --objects tree,
// ot_build.comp then builds the object tree over these spheres). Compiled with RH_MESH_SPHERES (--objects meshes): one
// thread per object (a run of at most 4096 consecutive triangles, ray_hierarchy_renderer.cpp) writes the sphere
// bounding its triangles' spheres.
#include "rh_common.glsl"
#include "rh_triangles.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_SPHERES) buffer Spheres { vec4 rh_spheres[]; };
layout(std430, binding = RH_BINDING_OBJECTS) buffer Objects { RhObject rh_objects[]; };

uniform uint rh_count;

void main() {
    const uint i = rt_global_index();
    if (i >= rh_count) return;
#ifndef RH_MESH_SPHERES
    vec3 a, b, c;
    rh_load_triangle(i, a, b, c);
    rh_spheres[i] = rh_triangle_sphere(a, b, c);
#else
    RhObject o = rh_objects[i];
    vec3 lo = vec3(RT_INFINITY), hi = vec3(-RT_INFINITY);
    for (uint k = 0u; k < o.count; ++k) {
        const vec4 s = rh_spheres[o.first + k];
        lo = min(lo, s.xyz - s.w);
        hi = max(hi, s.xyz + s.w);
    }
    const vec3 m = 0.5 * lo + 0.5 * hi;
    float r = 0.0;
    for (uint k = 0u; k < o.count; ++k) {
        const vec4 s = rh_spheres[o.first + k];
        r = max(r, length(s.xyz - m) + s.w);
    }
    o.sphere = vec4(m, r * (1.0 + RH_PAD) + RH_PAD * max(rh_max_abs(m), rh_max_abs(hi - lo)) + 1e-30);
    rh_objects[i] = o;
#endif
}
