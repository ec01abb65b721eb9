// The wavefront Whitted pipeline's data on the GPU (rt::gpu::Wavefront, common/gpu/wavefront.h): ray and hit queues,
// the per-pixel radiance accumulator, the settings, and the hook through which a traversal counts its tests.
//
// Instead of one thread following a whole ray tree (stage 01's recursion), each pass handles one kind of work for
// every ray that needs it (Laine, Karras & Aila 2013, "Megakernels Considered Harmful"):
//   shade.comp   hits -> light contributions, shadow rays, next bounce's reflection/refraction rays
//   shadow.comp  shadow rays -> any hit; the light's contribution when unoccluded
//   trace.comp   reflection/refraction rays -> closest hit -> the hit queue for the next shade pass
// Queues are appended to with an atomic counter (an append, not a prefix sum: the order of entries then varies from
// run to run, but every pass treats its entries independently and the radiance sum below is order independent).
#include "bindings.glsl"
#include "counters.glsl"
#include "compute.glsl"
#include "intersect.glsl"

// SSBO bindings of the pipeline; a stage's traversal data start at WF_BINDING_TRAVERSAL_FIRST
// (rt::gpu::kWavefrontBindingTraversalFirst).
#define WF_BINDING_RAYS_IN (RT_BINDING_STAGE_FIRST + 0)
#define WF_BINDING_HITS (RT_BINDING_STAGE_FIRST + 1)
#define WF_BINDING_RAYS_OUT (RT_BINDING_STAGE_FIRST + 2)
#define WF_BINDING_SHADOW_RAYS (RT_BINDING_STAGE_FIRST + 3)
#define WF_BINDING_RADIANCE (RT_BINDING_STAGE_FIRST + 4)
#define WF_BINDING_QUEUE_COUNTS (RT_BINDING_STAGE_FIRST + 5)
#define WF_BINDING_IMAGE (RT_BINDING_STAGE_FIRST + 6)
#define WF_BINDING_TRAVERSAL_FIRST (RT_BINDING_STAGE_FIRST + 8)

// Ray kinds, as rt::RayKind.
#define WF_KIND_PRIMARY 0u
#define WF_KIND_SHADOW 1u
#define WF_KIND_REFLECTION 2u
#define WF_KIND_REFRACTION 3u

// A queued ray (48 bytes, std430; WavefrontRay in wavefront.h). For shadow rays `weight` is the light's whole
// contribution to the pixel (path weight times the unshadowed light), added when nothing blocks the ray.
struct WavefrontRay {
    vec3 origin; float tmax;
    vec3 direction; uint pixel;
    vec3 weight; uint depth_kind;   // depth in bits 0-15, kind in bits 16-31
};

// A ray and what it hit (64 bytes): the input of the shade pass.
struct WavefrontHit {
    WavefrontRay ray;
    int triangle; float t; float u; float v;
};

layout(std430, binding = WF_BINDING_RAYS_IN) buffer WfRaysIn { WavefrontRay wf_rays_in[]; };
layout(std430, binding = WF_BINDING_HITS) buffer WfHits { WavefrontHit wf_hits[]; };
layout(std430, binding = WF_BINDING_RAYS_OUT) buffer WfRaysOut { WavefrontRay wf_rays_out[]; };
layout(std430, binding = WF_BINDING_SHADOW_RAYS) buffer WfShadowRays { WavefrontRay wf_shadow_rays[]; };
// Radiance of the current sample, 3 ints per pixel in fixed point (see wf_accumulate).
layout(std430, binding = WF_BINDING_RADIANCE) buffer WfRadiance { int wf_radiance[]; };
// Append counters of the output queues; the CPU zeroes them before a pass and reads them after it.
layout(std430, binding = WF_BINDING_QUEUE_COUNTS) buffer WfQueueCounts {
    uint wf_count_hits;
    uint wf_count_rays_out;
    uint wf_count_shadow_rays;
    uint wf_count_pad;
};
// Sum over the samples of the pixel's radiance (rgb; a = unused), float, written only by resolve.comp.
layout(std430, binding = WF_BINDING_IMAGE) buffer WfImage { vec4 wf_image[]; };

// Settings (uniforms set by rt::gpu::Wavefront). RT_INTERSECT_METHOD (a define: RT_INTERSECT_MOLLER or
// RT_INTERSECT_WATERTIGHT) picks the ray/triangle test at compile time.
uniform uint wf_input_count;        // entries in the pass's input queue
uniform int wf_max_depth;           // --max-depth
uniform float wf_cutoff;            // --cutoff
uniform int wf_fresnel;             // RT_FRESNEL_SCHLICK | RT_FRESNEL_EXACT
uniform int wf_offset;              // RT_OFFSET_EPSILON | RT_OFFSET_ROBUST
uniform float wf_epsilon;           // --epsilon
uniform ivec2 wf_image_size;        // width, height
uniform vec2 wf_sample_offset;      // where in the pixel this sample's primary rays pass (pixel_samples.h)

uint wf_depth(WavefrontRay r) { return r.depth_kind & 0xffffu; }
uint wf_kind(WavefrontRay r) { return r.depth_kind >> 16; }

WavefrontRay wf_make_ray(vec3 origin, vec3 direction, float tmax, vec3 weight, uint pixel, uint depth, uint kind) {
    WavefrontRay r;
    r.origin = origin;
    r.tmax = tmax;
    r.direction = direction;
    r.pixel = pixel;
    r.weight = weight;
    r.depth_kind = (depth & 0xffffu) | (kind << 16);
    return r;
}

Ray wf_ray(WavefrontRay r) { return make_ray(r.origin, r.direction, r.tmax); }

// Appends to the queues. The CPU sizes each queue for the most entries its pass can write, so the bounds checks
// never drop anything; they only keep a bug from writing past a buffer.
void wf_push_hit(WavefrontRay r, Hit h) {
    const uint slot = atomicAdd(wf_count_hits, 1u);
    if (slot < uint(wf_hits.length())) {
        WavefrontHit e;
        e.ray = r;
        e.triangle = h.triangle;
        e.t = h.t;
        e.u = h.u;
        e.v = h.v;
        wf_hits[slot] = e;
    }
}
void wf_push_ray(WavefrontRay r) {
    const uint slot = atomicAdd(wf_count_rays_out, 1u);
    if (slot < uint(wf_rays_out.length())) wf_rays_out[slot] = r;
}
void wf_push_shadow_ray(WavefrontRay r) {
    const uint slot = atomicAdd(wf_count_shadow_rays, 1u);
    if (slot < uint(wf_shadow_rays.length())) wf_shadow_rays[slot] = r;
}

// Adds radiance to a pixel. Deterministic whatever order the GPU runs the threads in: integer addition is
// associative, so each contribution is rounded to a multiple of 2^-16 (1.5e-5, a twentieth of the smallest step of
// an 8-bit sRGB value) and added with an integer atomicAdd. A pixel's sum must stay below 32768 per sample.
const float WF_FIXED_SCALE = 65536.0;
void wf_accumulate(uint pixel, vec3 c) {
    const ivec3 q = ivec3(round(clamp(c, vec3(-32767.0), vec3(32767.0)) * WF_FIXED_SCALE));
    if (q.x != 0) atomicAdd(wf_radiance[3u * pixel], q.x);
    if (q.y != 0) atomicAdd(wf_radiance[3u * pixel + 1u], q.y);
    if (q.z != 0) atomicAdd(wf_radiance[3u * pixel + 2u], q.z);
}

// Counting ray/triangle tests: a traversal calls wf_count_tests(n) for the tests it makes; each pass adds the
// thread's total to the global counter once, at its end (one atomic per thread, not per test). Compiled out
// without COUNT_TESTS (timing runs).
uint wf_tests = 0u;
void wf_count_tests(uint n) {
#ifdef COUNT_TESTS
    wf_tests += n;
#endif
}
void wf_flush_tests() {
#ifdef COUNT_TESTS
    rt_counter_add(RT_COUNTER_INTERSECTION_TESTS, wf_tests);
#endif
}
