// The wavefront Whitted pipeline's data on the GPU (rt::gpu::Wavefront, common/gpu/pipeline/wavefront.h): ray and hit
// queues, the per-pixel radiance accumulator, the settings, and the hook through which a traversal counts its tests.
//
// Instead of one thread following a whole ray tree (stage 01's recursion), each pass handles one kind of work for
// every ray that needs it (Laine, Karras & Aila 2013, "Megakernels Considered Harmful"):
//   shade.comp           hits -> light contributions, shadow rays, next bounce's reflection/refraction rays
//   shadow.comp          shadow rays -> any hit (one result per ray); shadow_collect.comp adds the unblocked lights
//   trace.comp           reflection/refraction rays -> closest hit (one result per ray); trace_collect.comp turns
//                        the results into the next shade pass' hits and adds the background of the misses
// Passes never append: a pass writes its outputs to fixed slots (a slot per input and output kind), flags the used
// ones, and compact_records.comp packs them with a prefix sum, so every queue has the same order on every run
// (docs/gpu.md, "Queue order").
#include "common/shaders/bindings.glsl"
#include "common/shaders/counters.glsl"
#include "common/shaders/compute.glsl"
#include "common/shaders/trace/intersect.glsl"

// SSBO bindings of the pipeline; a stage's traversal data start at WF_BINDING_TRAVERSAL_FIRST
// (rt::gpu::kWavefrontBindingTraversalFirst). wavefront.cpp has the same numbers.
#define WF_BINDING_RAYS_IN (RT_BINDING_STAGE_FIRST + 0)
#define WF_BINDING_HITS (RT_BINDING_STAGE_FIRST + 1)
#define WF_BINDING_RAY_SLOTS (RT_BINDING_STAGE_FIRST + 2)
#define WF_BINDING_FLAGS (RT_BINDING_STAGE_FIRST + 3)
#define WF_BINDING_RADIANCE (RT_BINDING_STAGE_FIRST + 4)
#define WF_BINDING_RESULTS (RT_BINDING_STAGE_FIRST + 5)
#define WF_BINDING_IMAGE (RT_BINDING_STAGE_FIRST + 6)
#define WF_BINDING_TESTS_PER_PIXEL (RT_BINDING_STAGE_FIRST + 7)
#define WF_BINDING_TRAVERSAL_FIRST (RT_BINDING_STAGE_FIRST + 8)

// Ray kinds, as rt::RayKind.
#define WF_KIND_PRIMARY 0u
#define WF_KIND_SHADOW 1u
#define WF_KIND_REFLECTION 2u
#define WF_KIND_REFRACTION 3u
#define WF_KIND_TRANSPARENCY 4u   // the continuation through a BLEND surface

// The pixel of an unused slot (a tile slot outside the image).
#define WF_NO_PIXEL 0xffffffffu

// A queued ray (64 bytes, std430; WavefrontRay in wavefront.h). For shadow rays `weight` is the light's whole
// contribution to the pixel (path weight times the unshadowed light), added when nothing blocks the ray.
// `path`, `light` and `light_sample` name the ray in the ray tree (common/trace/hit_record.h): path 1 is the primary
// ray, 2p and 2p + 1 the reflection and refraction (on a BLEND surface: transparency) children of path p (meaningful
// up to depth 30); a shadow ray has its parent hit's path, the index of its light and, for an area light, the cell
// of the light's grid it aims at (0 otherwise).
struct WavefrontRay {
    vec3 origin; float tmax;
    vec3 direction; uint pixel;
    vec3 weight; uint depth_kind;   // depth in bits 0-15, kind in bits 16-31
    uint path; uint light; uint light_sample; uint pad1;
};

// A ray and what it hit (80 bytes): the input of the shade pass.
struct WavefrontHit {
    WavefrontRay ray;
    int triangle; float t; float u; float v;
};

// What a trace pass finds for one ray (16 bytes; WavefrontTraceResult in wavefront.h): triangle -1 for a miss.
struct WavefrontTraceResult {
    int triangle; float t; float u; float v;
};

layout(std430, binding = WF_BINDING_RAYS_IN) buffer WfRaysIn { WavefrontRay wf_rays_in[]; };
layout(std430, binding = WF_BINDING_HITS) buffer WfHits { WavefrontHit wf_hits[]; };
layout(std430, binding = WF_BINDING_RAY_SLOTS) buffer WfRaySlots { WavefrontRay wf_ray_slots[]; };
// One flag per output slot of the pass (1 = used), the input of the compaction.
layout(std430, binding = WF_BINDING_FLAGS) buffer WfFlags { uint wf_flags[]; };
// Radiance of the current sample: per pixel and channel a 96-bit fixed-point number (see wf_accumulate).
layout(std430, binding = WF_BINDING_RADIANCE) buffer WfRadiance { uint wf_radiance[]; };
// Sum over the samples of the pixel's radiance (rgb; a = unused), float, written only by resolve.comp (for the band
// of rows of wf_radiance).
layout(std430, binding = WF_BINDING_IMAGE) buffer WfImage { vec4 wf_image[]; };
#ifdef RECORD_TESTS_PER_PIXEL
// Ray/triangle tests of all rays of each pixel's tree (--heatmap).
layout(std430, binding = WF_BINDING_TESTS_PER_PIXEL) buffer WfTestsPerPixel { uint wf_tests_per_pixel[]; };
#endif

// Settings (uniforms set by rt::gpu::Wavefront). RT_INTERSECT_METHOD (a define: RT_INTERSECT_MOLLER or
// RT_INTERSECT_WATERTIGHT) picks the ray/triangle test at compile time.
uniform uint wf_input_first;        // first entry of the pass's input queue (wf_rays_in)
uniform uint wf_input_count;        // entries in the pass's input queue
uniform int wf_max_depth;           // --max-depth
uniform float wf_cutoff;            // --cutoff
uniform int wf_fresnel;             // RT_FRESNEL_SCHLICK | RT_FRESNEL_EXACT
uniform int wf_offset;              // RT_OFFSET_EPSILON | RT_OFFSET_ROBUST
uniform float wf_epsilon;           // --epsilon
uniform ivec2 wf_image_size;        // width, height
uniform vec2 wf_sample_offset;      // where in the pixel this sample's primary rays pass (pixel_samples.h)
uniform uint wf_tile_first;         // primary passes: the first 8x8 tile of this batch (see wf_tile_pixel)
uniform uint wf_pixel_first;        // the first pixel of the band of rows wf_radiance holds (see wf_accumulate)

uint wf_depth(WavefrontRay r) { return r.depth_kind & 0xffffu; }
uint wf_kind(WavefrontRay r) { return r.depth_kind >> 16; }

WavefrontRay wf_make_ray(vec3 origin, vec3 direction, float tmax, vec3 weight, uint pixel, uint depth, uint kind,
                         uint path, uint light) {
    WavefrontRay r;
    r.origin = origin;
    r.tmax = tmax;
    r.direction = direction;
    r.pixel = pixel;
    r.weight = weight;
    r.depth_kind = (depth & 0xffffu) | (kind << 16);
    r.path = path;
    r.light = light;
    r.light_sample = 0u;
    r.pad1 = 0u;
    return r;
}

// The ray's name in the ray tree without its path (HitRecord::kind_light: kind, light, light sample).
uint wf_kind_light(uint kind, uint light, uint light_sample) { return kind | (light & 0xffffu) << 8u | light_sample << 24u; }

Ray wf_ray(WavefrontRay r) { return make_ray(r.origin, r.direction, r.tmax); }

// The order of primary rays and hits: the image in 8x8 tiles, row by row, and inside a tile the Morton (Z) order of
// the pixel, so 2x2, 4x4 and 8x8 blocks of neighbouring pixels are neighbours in the queue. Slot s of a primary
// batch is pixel wf_tile_pixel(wf_tile_first * 64 + s); false for the slots of edge tiles outside the image.
uint wf_compact_bits(uint v) {   // the even bits of v, packed (Morton decode)
    v &= 0x55555555u;
    v = (v | (v >> 1)) & 0x33333333u;
    v = (v | (v >> 2)) & 0x0f0f0f0fu;
    v = (v | (v >> 4)) & 0x00ff00ffu;
    v = (v | (v >> 8)) & 0x0000ffffu;
    return v;
}
bool wf_tile_pixel(uint slot, out ivec2 p) {
    const uint tiles_x = (uint(wf_image_size.x) + 7u) / 8u;
    const uint tile = slot / 64u, inside = slot % 64u;
    p = ivec2(int((tile % tiles_x) * 8u + wf_compact_bits(inside)),
              int((tile / tiles_x) * 8u + wf_compact_bits(inside >> 1)));
    return p.x < wf_image_size.x && p.y < wf_image_size.y;
}

// Adds radiance to a pixel, exactly and in any thread order. Each channel of a pixel is a 96-bit unsigned fixed-point
// number in three 32-bit limbs (least significant first), in units of 2^-32: resolution 2^-32 (2.3e-10), range
// [0, 2^63) (9.2e18, beyond any photometric scene: a 1e7 cd lamp at 1 mm gives 1e13). A contribution is rounded to
// the resolution and added limb by limb with atomicAdd; the value atomicAdd returns tells whether the limb wrapped,
// and the carry goes to the next limb. Integer addition is associative, so the sum does not depend on the order the
// GPU runs the threads in. Bit 31 of the top limb (2^63) is sticky: a sum that reaches it, or a carry out of the top
// limb, sets it, and resolve.comp then gives the saturated value WF_RADIANCE_MAX, never a wrapped one. Negative and
// NaN contributions add nothing (scenes have non-negative colours and lights); +Inf saturates. wf_radiance holds a
// band of image rows starting at pixel wf_pixel_first (the whole image unless it would not fit one storage block).
const float WF_RADIANCE_MAX = 9.2233720e18;   // 2^63, kMaxSampleRadiance (common/trace/shading.h): 01 clamps there too
void wf_add_fixed(uint base, float c) {
    if (!(c > 0.0)) return;   // also NaN
    if (c >= WF_RADIANCE_MAX) {
        atomicOr(wf_radiance[base + 2u], 0x80000000u);
        return;
    }
    int e;
    const float m = frexp(c, e);               // c = m 2^e, 0.5 <= m < 1
    uint mantissa = uint(m * 16777216.0);      // 24 bits, exact: c 2^32 = mantissa 2^(e + 8)
    int shift = e + 8;
    if (shift < 0) {                           // below 1 unit: round to nearest
        if (shift < -24) return;
        mantissa = (mantissa + (1u << uint(-shift - 1))) >> uint(-shift);
        shift = 0;
    }
    uint limbs[3] = uint[3](0u, 0u, 0u);
    const int q = shift / 32, r = shift % 32;   // shift <= 71: the mantissa ends below bit 95
    limbs[q] = mantissa << uint(r);
    if (r > 0 && q < 2) limbs[q + 1] = mantissa >> uint(32 - r);
    uint carry = 0u;
    for (uint k = 0u; k < 3u; ++k) {
        const uint add = limbs[k] + carry;
        carry = add < limbs[k] ? 1u : 0u;   // limbs[k] = 0xffffffff plus a carry: 0 here, 1 to the next limb
        if (add != 0u) {
            const uint old = atomicAdd(wf_radiance[base + k], add);
            if (old + add < old) carry += 1u;
        }
    }
    if (carry != 0u) atomicOr(wf_radiance[base + 2u], 0x80000000u);
}
void wf_accumulate(uint pixel, vec3 c) {
    const uint base = 9u * (pixel - wf_pixel_first);
    wf_add_fixed(base, c.r);
    wf_add_fixed(base + 3u, c.g);
    wf_add_fixed(base + 6u, c.b);
}

// Mesa's llvmpipe ends the loops of one shader invocation silently once they have run 65,535 iterations in all
// (docs/gpu.md, "Known limit"); after that every loop runs its body once and stops. An invocation that looped more
// (a brute-force ray over 100,000 triangles) would give a wrong answer with no error, so each pass that runs a
// traversal or a loop over lights ends with wf_check_loop_budget(): a loop of wf_loop_probe (2, a uniform, so the
// compiler cannot unroll it) iterations runs only once when the budget is spent, and the invocation is then counted
// in RT_COUNTER_LOOPS_CUT. Wavefront::finish_frame refuses a frame with any such invocation. On drivers without the
// limit the probe always runs twice.
uniform uint wf_loop_probe;
void wf_check_loop_budget() {
    uint runs = 0u;
    for (uint i = 0u; i < wf_loop_probe; ++i) ++runs;
    if (runs != wf_loop_probe) rt_counter_add(RT_COUNTER_LOOPS_CUT, 1u);
}

// --pixel X,Y (WATCH_PIXEL, with RECORD_TESTS_PER_PIXEL): what each ray of that pixel costs, for the ray tree the
// driver prints. After the per-pixel counts, wf_tests_per_pixel holds at wf_watch_base the number of entries used,
// then WF_WATCH_CAPACITY entries of 6 uints: (path, wf_kind_light, tests lo, tests hi, steps, unused), the key
// named as the ray's HitRecord (hit_record.h). A part for a key already listed is added to it; two threads adding the
// first part of one key at once may make two entries, which the CPU adds up. Drained after every sample.
#ifdef WATCH_PIXEL
#define WF_WATCH_CAPACITY 65536u
#define WF_WATCH_ENTRY 6u
uniform uint wf_watch_pixel;   // y * width + x
uniform uint wf_watch_base;    // the number of pixels
void wf_watch(uint pixel, uint path, uint kind_light, uint tests, uint steps) {
    if (pixel != wf_watch_pixel) return;
    uint entry = 0xffffffffu;
    const uint used = min(wf_tests_per_pixel[wf_watch_base], WF_WATCH_CAPACITY);
    for (uint e = 0u; e < used && entry == 0xffffffffu; ++e) {
        const uint at = wf_watch_base + 1u + e * WF_WATCH_ENTRY;
        if (wf_tests_per_pixel[at] == path && wf_tests_per_pixel[at + 1u] == kind_light) entry = e;
    }
    if (entry == 0xffffffffu) {
        entry = atomicAdd(wf_tests_per_pixel[wf_watch_base], 1u);
        if (entry >= WF_WATCH_CAPACITY) return;   // the CPU sees the count beyond the capacity and refuses the frame
        const uint at = wf_watch_base + 1u + entry * WF_WATCH_ENTRY;
        wf_tests_per_pixel[at] = path;
        wf_tests_per_pixel[at + 1u] = kind_light;
    }
    const uint at = wf_watch_base + 1u + entry * WF_WATCH_ENTRY;
    const uint old = atomicAdd(wf_tests_per_pixel[at + 2u], tests);
    if (old + tests < old) atomicAdd(wf_tests_per_pixel[at + 3u], 1u);
    atomicAdd(wf_tests_per_pixel[at + 4u], steps);
}
#endif

// Counting ray/triangle tests: a traversal calls wf_count_tests(n) for the tests it makes (and wf_count_steps(n) for
// its own steps, 03's grid cells, which only --pixel reports); each pass adds the thread's total to the global
// counter and to its ray kind's once, at its end (one atomic each per thread, not per test), and with
// RECORD_TESTS_PER_PIXEL (--heatmap) to the ray's pixel. Compiled out without COUNT_TESTS (timing runs).
uint wf_tests = 0u, wf_steps = 0u;
void wf_count_tests(uint n) {
#ifdef COUNT_TESTS
    wf_tests += n;
#endif
}
void wf_count_steps(uint n) {
#ifdef WATCH_PIXEL
    wf_steps += n;
#endif
}
void wf_flush_tests(uint pixel, uint kind, uint path, uint kind_light) {
#ifdef COUNT_TESTS
    rt_counter_add(RT_COUNTER_INTERSECTION_TESTS, wf_tests);
    rt_counter_add(RT_COUNTER_TESTS_FIRST + kind, wf_tests);
#ifdef RECORD_TESTS_PER_PIXEL
    if (wf_tests != 0u && pixel != WF_NO_PIXEL) atomicAdd(wf_tests_per_pixel[pixel], wf_tests);
#endif
#ifdef WATCH_PIXEL
    wf_watch(pixel, path, kind_light, wf_tests, wf_steps);
#endif
#endif
}
// The same for the one ray a thread of a per-ray pass traced.
void wf_flush_ray_tests(WavefrontRay r) {
    wf_flush_tests(r.pixel, wf_kind(r), r.path, wf_kind_light(wf_kind(r), r.light, r.light_sample));
}
