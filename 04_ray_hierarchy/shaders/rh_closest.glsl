// The closest-hit state of each ray of a batch, shared by the leaf and fold passes. Brute force (brute_force.glsl)
// walks the triangles in id order, each hit shrinking tmax for the next, and replaces its hit only when strictly
// closer. The leaf pairs come in any order, so the same answer is found in two steps:
//   1. rh_leaf.comp tests every surviving (ray, triangle) pair with the ray's own tmax, keeps the smallest t
//      (atomicMin on its bits: positive floats order as their bits) and lists the hits within RH_TIE_RANGE of it;
//   2. rh_fold.comp then replays brute force's fold over the listed hits of each ray in increasing triangle id
//      (one per round), which gives exactly brute force's hit: hits farther than RH_TIE_RANGE beyond the closest
//      never decide anything there (the watertight test's tmax check can reject a closer hit only within a few ulps
//      of the kept one; stage 03's grid.glsl has the same two phases).
// With cut-outs, step 1 lists only opaque hits (rh_leaf.comp applies opacity.glsl). Step 2 needs no opacity test of
// its own: it tests only listed triangles again, and a test gives the same u, v whatever tmax lets it through, so a
// listed hit stays opaque; brute force over the opaque hits is what the fold replays.
#include "rh_info.glsl"

#define RH_TIE_RANGE 1e-5

struct RhRayState {
    uint min_t;     // bits of the smallest t found (0x7f800000 = +inf: none yet)
    uint cursor;    // the fold has handled the listed hits with triangle < cursor
    uint next;      // the next triangle to fold (0xffffffff: none)
    int triangle;   // the fold's hit so far (-1: none)
    float t, u, v;
    uint pad;
};

// A listed hit: the ray (index in the batch), the triangle, the bits of t.
layout(std430, binding = RH_BINDING_HITS) buffer Hits { uvec4 rh_hits[]; };
layout(std430, binding = RH_BINDING_STATE) buffer State { RhRayState rh_state[]; };

bool rh_near(float t, uint min_t) {
    precise float reach = uintBitsToFloat(min_t) * (1.0 + RH_TIE_RANGE);
    return t <= reach;
}

bool rh_intersect(Ray ray, uint tri, out float t, out float u, out float v) {
    vec3 a, b, c;
    rh_load_triangle(tri, a, b, c);
    return intersect_triangle(RT_INTERSECT_METHOD, ray, a, b, c, t, u, v);
}
