#version 450 core
// Primary hits from the G-buffer: one thread per pixel, in the pipeline's primary order: slot s of the batch is the
// pixel wf_tile_pixel(wf_tile_first * 64 + s) (8x8 tiles, Morton order inside), and compaction of the flagged slots
// gives the hit queue that order.
//
// Rasterization tells which triangles can be seen around the pixel, not exactly which one its camera ray hits.
// The rasterizer snaps vertices to a subpixel grid (8 bits of fraction on most GPUs) and, for a sample exactly on
// an edge shared by two triangles, gives it to one of them by its fill rule (top-left); a ray, tested against the
// exact vertices, meets both at the same t, and brute force (brute_force.glsl, rt::BruteForceTracer) keeps the
// lowest triangle id. So, at edges and silhouettes, the G-buffer's triangle may not be the ray's. The pixel's exact
// camera ray (camera.glsl, the twin of rt::camera_ray) is therefore intersected, with the shared ray/triangle test,
// with every distinct triangle of the 3x3 G-buffer neighbourhood of the pixel (its own included): a triangle the
// ray hits but the rasterizer gave to the pixel next door is in that neighbourhood. The closest hit is kept, ties
// to the lowest id, as brute force does. One case remains: a sliver triangle seen edge-on at a silhouette that no
// pixel rasterizes. The ray then misses the pixel's own G-buffer triangle and finds nothing (or something behind)
// though the rasterizer saw a surface there: the point where the ray meets that triangle's plane stands in for
// the sliver's hit, as close to it as shading needs. These tests are counted (wf_count_tests), like a traversal's;
// the rays stay "rasterized" in the stats (docs/gpu.md).
#include "common/shaders/wavefront/wavefront.glsl"
#include "common/shaders/trace/scene.glsl"
#include "common/shaders/trace/environment.glsl"

layout(local_size_x = 64) in;

layout(binding = RT_TEXTURE_UNIT_STAGE_FIRST) uniform usampler2D gbuffer_triangle_ids;   // triangle + 1, 0 = none

// Where the ray meets the plane of triangle (a, b, c): Moller-Trumbore without its inside tests; false when the
// ray runs along the plane or meets it behind the origin.
bool plane_hit(Ray ray, vec3 a, vec3 b, vec3 c, out float t, out float u, out float v) {
    precise vec3 e1 = b - a;
    precise vec3 e2 = c - a;
    precise vec3 p = rt_cross(ray.direction, e2);
    precise float det = rt_dot(e1, p);
    if (det == 0.0) return false;
    precise float inv_det = 1.0 / det;
    precise vec3 s = ray.origin - a;
    precise vec3 q = rt_cross(s, e1);
    u = rt_dot(s, p) * inv_det;
    v = rt_dot(ray.direction, q) * inv_det;
    t = rt_dot(e2, q) * inv_det;
    return t > 0.0 && rt_isfinite(t);
}

// The distinct triangles of the 3x3 pixels around p (clamped to the image), in increasing id order; returns how
// many.
uint neighbourhood_triangles(ivec2 p, out uint ids[9]) {
    uint n = 0u;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), wf_image_size - 1);
            const uint id = texelFetch(gbuffer_triangle_ids, q, 0).r;   // triangle + 1, 0 = none
            if (id == 0u) continue;
            bool seen = false;
            for (uint j = 0u; j < n; ++j) seen = seen || ids[j] == id - 1u;
            if (seen) continue;
            uint k = n;   // insertion sort
            while (k > 0u && ids[k - 1u] > id - 1u) {
                ids[k] = ids[k - 1u];
                --k;
            }
            ids[k] = id - 1u;
            ++n;
        }
    return n;
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
#ifdef ENABLE_CUTOUTS
        wf_ray_slots[slot] = e.ray;   // not deferred
#endif
        return;
    }
    const uint pixel = uint(p.y * wf_image_size.x + p.x);
    precise float x = float(p.x) + wf_sample_offset.x;
    precise float y = float(p.y) + wf_sample_offset.y;
    Ray ray = camera_ray(rt_camera, wf_image_size.x, wf_image_size.y, x, y);
    e.ray = wf_make_ray(ray.origin, ray.direction, RT_INFINITY, vec3(1.0), pixel, 0u, WF_KIND_PRIMARY, 1u, 0u);

    // BEGIN EXERCISE 02.primary_hits: intersect the pixel's camera ray with every distinct triangle of the 3x3
    // G-buffer neighbourhood (neighbourhood_triangles), keeping the closest (ties: the lowest id), then the sliver
    // case; fill e.triangle, e.t, e.u, e.v and count the tests (wf_count_tests).
    // Brute force over the candidates, in id order as brute_force.glsl: a hit must be strictly closer than the
    // closest so far (checked again after the test, whose scaled t < tmax may round an equal t through), so at an
    // equal t the lowest id stays.
    uint ids[9];
    const uint n = neighbourhood_triangles(p, ids);
    for (uint k = 0u; k < n; ++k) {
        vec3 a, b, c;
        load_triangle(ids[k], a, b, c);
        float t, u, v;
        if (intersect_triangle(RT_INTERSECT_METHOD, ray, a, b, c, t, u, v) && (e.triangle < 0 || t < e.t)) {
            ray.tmax = t;
            e.triangle = int(ids[k]);
            e.t = t;
            e.u = u;
            e.v = v;
        }
    }
    // The sliver case (see the top): the G-buffer's own triangle, missed, but its plane in front of any hit found,
    // by more than rounding (a relative 1e-4: where two surfaces meet, at a corner, the plane of one and the other's
    // hit are a few ulps apart, and the hit found is the right one).
    const uint own = texelFetch(gbuffer_triangle_ids, p, 0).r;   // triangle + 1, 0 = none
    if (own != 0u && e.triangle != int(own - 1u)) {
        vec3 a, b, c;
        load_triangle(own - 1u, a, b, c);
        float t, u, v;
        if (plane_hit(ray, a, b, c, t, u, v) && (e.triangle < 0 || t < e.t * (1.0 - 1e-4))) {
            e.triangle = int(own - 1u);
            e.t = t;
            e.u = u;
            e.v = v;
        }
    }
    wf_count_tests(n);
    // STUB: e.triangle = -1;
    // END EXERCISE
    wf_flush_tests(pixel, WF_KIND_PRIMARY, 1u, wf_kind_light(WF_KIND_PRIMARY, 0u, 0u));
#ifdef ENABLE_CUTOUTS
    // Cut-outs (docs/gpu.md, "Cut-outs in stage 02"): the G-buffer knows nothing of opacity, and the raster's uv is not
    // the ray's, so it cannot say whether the ray passes through a MASK or BLEND surface. The closest candidate above
    // ignores opacity; when it is such a surface, the pixel's camera ray is deferred: written to its ray slot and
    // traced by the stage's traversal (which applies the opacity test, opacity.glsl) after the rasterized hits are
    // shaded, as stage 03 traces all of them with --primary trace. A pixel whose candidate is opaque keeps it: no hit
    // in front of it was missed (a transparent hit can only remove hits, never add one), so it is exact as before.
    WavefrontRay deferred = e.ray;
    deferred.pixel = WF_NO_PIXEL;
    if (e.triangle >= 0 && rt_materials[rt_material_ids[uint(e.triangle)]].alpha_mode != RT_ALPHA_OPAQUE) {
        deferred = e.ray;
        e.ray.pixel = WF_NO_PIXEL;   // its primary record comes from the trace pass (--dump-hits)
        wf_ray_slots[slot] = deferred;
        wf_hits[slot] = e;
        wf_flags[slot] = 0u;
        return;
    }
    wf_ray_slots[slot] = deferred;
#endif
    wf_hits[slot] = e;
    wf_flags[slot] = e.triangle >= 0 ? 1u : 0u;
    if (e.triangle < 0) wf_accumulate(pixel, rt_miss_radiance(ray.direction));   // kept with triangle -1 for the hit records
}
