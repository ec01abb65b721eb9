#version 450 core
// Primary hits from the G-buffer: one thread per pixel, in the pipeline's primary order: slot s of the batch is the
// pixel wf_tile_pixel(wf_tile_first * 64 + s) (8x8 tiles, Morton order inside), and compaction of the flagged slots
// gives the hit queue that order. Rasterization says which triangle the primary ray hits;
// the barycentrics are then computed as the CPU computes them, by intersecting the same camera ray (camera.glsl,
// the twin of rt::camera_ray) with that triangle, using the same ray/triangle test. At the few edge pixels where
// rasterization and the ray test disagree, the ray meets the triangle's plane just outside it: the plane's
// barycentrics are used. Pixels with no triangle see the background.
#include "wavefront/wavefront.glsl"
#include "scene.glsl"

layout(local_size_x = 64) in;

layout(binding = RT_TEXTURE_UNIT_STAGE_FIRST) uniform usampler2D gbuffer_triangle_ids;   // triangle + 1, 0 = none

// Where the ray meets the plane of triangle (a, b, c): Moller-Trumbore without its inside tests.
void plane_hit(Ray ray, vec3 a, vec3 b, vec3 c, out float t, out float u, out float v) {
    precise vec3 e1 = b - a;
    precise vec3 e2 = c - a;
    precise vec3 p = rt_cross(ray.direction, e2);
    precise float det = rt_dot(e1, p);
    if (det == 0.0) {   // seen edge-on: any point of the triangle will do
        t = 0.0;
        u = 1.0 / 3.0;
        v = 1.0 / 3.0;
        return;
    }
    precise float inv_det = 1.0 / det;
    precise vec3 s = ray.origin - a;
    precise vec3 q = rt_cross(s, e1);
    u = rt_dot(s, p) * inv_det;
    v = rt_dot(ray.direction, q) * inv_det;
    t = rt_dot(e2, q) * inv_det;
}

void main() {
    const uint slot = rt_global_index();
    if (slot >= wf_input_count) return;
    WavefrontHit e;
    e.triangle = -1;
    e.t = 0.0;
    e.u = 0.0;
    e.v = 0.0;
    ivec2 p;
    if (!wf_tile_pixel(wf_tile_first * 64u + slot, p)) {   // outside the image
        e.ray = wf_make_ray(vec3(0.0), vec3(0.0), 0.0, vec3(0.0), WF_NO_PIXEL, 0u, WF_KIND_PRIMARY, 1u, 0u);
        wf_hits[slot] = e;
        wf_flags[slot] = 0u;
        return;
    }
    const uint pixel = uint(p.y * wf_image_size.x + p.x);
    precise float x = float(p.x) + wf_sample_offset.x;
    precise float y = float(p.y) + wf_sample_offset.y;
    const Ray ray = camera_ray(rt_camera, wf_image_size.x, wf_image_size.y, x, y);
    e.ray = wf_make_ray(ray.origin, ray.direction, RT_INFINITY, vec3(1.0), pixel, 0u, WF_KIND_PRIMARY, 1u, 0u);
    const uint id = texelFetch(gbuffer_triangle_ids, p, 0).r;
    if (id == 0u) {   // kept with triangle -1 for the hit records
        wf_accumulate(pixel, rt_background);
        wf_hits[slot] = e;
        wf_flags[slot] = 0u;
        return;
    }
    vec3 a, b, c;
    load_triangle(id - 1u, a, b, c);
    Hit hit;
    if (!intersect_triangle(RT_INTERSECT_METHOD, ray, a, b, c, hit.t, hit.u, hit.v))
        plane_hit(ray, a, b, c, hit.t, hit.u, hit.v);
    e.triangle = int(id - 1u);
    e.t = hit.t;
    e.u = hit.u;
    e.v = hit.v;
    wf_hits[slot] = e;
    wf_flags[slot] = 1u;
}
