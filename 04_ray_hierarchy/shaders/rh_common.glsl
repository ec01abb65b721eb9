// The ray-space hierarchy's nodes and its conservative test (Roger, Assarsson & Holzschuch 2007, section 4), shared
// by every pass of the stage. C++ twin: ray_hierarchy.h / ray_hierarchy.cpp (the same formulas; tests check both).
//
// A node bounds a set of rays with 8 floats: a sphere (centre, radius) holding every origin and a cone (unit axis,
// spread angle) holding every direction. A leaf is one ray: radius 0 at its origin, spread 0 along its direction.
// radius < 0 marks an empty node (only rays with zero-length or non-finite directions or origins below it: such rays
// never hit anything in the exact test, so they are left out).
#include "common/shaders/wavefront/wavefront.glsl"

// The stage's SSBO bindings, from WF_BINDING_TRAVERSAL_FIRST (24) to 31 (Mesa allows 32 binding points; each pass
// uses a few). The leaf and fold passes reuse two points for their own buffers.
#define RH_BINDING_NODES (WF_BINDING_TRAVERSAL_FIRST + 0)     // RhNode[] of the levels being built or tested
#define RH_BINDING_SPHERES (WF_BINDING_TRAVERSAL_FIRST + 1)   // vec4 per triangle: its bounding sphere
#define RH_BINDING_OBJECTS (WF_BINDING_TRAVERSAL_FIRST + 2)   // RhObject[]: runs of triangles and their spheres
#define RH_BINDING_PAIRS (WF_BINDING_TRAVERSAL_FIRST + 3)     // uvec2[] (node, item) candidate pairs read
#define RH_BINDING_PAIRS_OUT (WF_BINDING_TRAVERSAL_FIRST + 4) // uvec2[] pairs written by the expansion
#define RH_BINDING_COUNTS (WF_BINDING_TRAVERSAL_FIRST + 5)    // uint[] per tested pair: children to expand, or 0
#define RH_BINDING_OFFSETS (WF_BINDING_TRAVERSAL_FIRST + 6)   // uint[] per work group: its first output place
#define RH_BINDING_INFO (WF_BINDING_TRAVERSAL_FIRST + 7)      // uint[8]: survivors, hit-list size, fold flag,
                                                              // scan total, fold tests per ray kind
#define RH_BINDING_ORDER RH_BINDING_NODES                     // expansion, tree build: triangle ids in leaf order
#define RH_BINDING_KEYS RH_BINDING_PAIRS                      // tree build: Morton codes
#define RH_BINDING_GROUP_OFFSETS RH_BINDING_PAIRS_OUT         // test pass: writes RH_BINDING_OFFSETS' buffer
#define RH_BINDING_HITS RH_BINDING_PAIRS_OUT                  // leaf and fold passes: the hit list
#define RH_BINDING_STATE RH_BINDING_COUNTS                    // leaf and fold passes: per-ray closest-hit state
#define RH_BINDING_CULL_ORDER RH_BINDING_COUNTS               // test pass writing children: as RH_BINDING_ORDER

// Relative padding of every bound and test (section "Conservative in floats" of README.md): 1e-4 is about 800 float
// ulps, far above the few ulps each formula loses and the error of GPU sin/cos/atan (~1e-6 absolute).
#define RH_PAD 1e-4
// A spread at or beyond this is taken as all directions (the cone test then accepts everything).
#define RH_ALL_DIRECTIONS 3.1415

struct RhNode {
    vec4 sphere;   // centre, radius (< 0: empty)
    vec4 cone;     // unit axis, spread angle in radians (>= RH_ALL_DIRECTIONS: every direction)
};

// An object node (object_tree.h, ObjectNode). Level 1 bounds triangles rh_order[first + k] (meshes: first + k);
// level l > 1 bounds object nodes [first, first + count) of level l - 1.
struct RhObject {   // object_tree.h: ObjectNode
    vec4 sphere;
    uint first, count, level, pad;
    vec4 box_lo, box_hi;   // its triangles' box (xyz), unpadded; all space for mesh objects
};

float rh_max_abs(vec3 v) { return max(abs(v.x), max(abs(v.y), abs(v.z))); }
bool rh_finite(vec3 v) { return rt_isfinite(v.x) && rt_isfinite(v.y) && rt_isfinite(v.z); }

RhNode rh_empty_node() { return RhNode(vec4(0.0, 0.0, 0.0, -1.0), vec4(1.0, 0.0, 0.0, 0.0)); }

// A leaf. The direction is scaled by its largest component before normalizing, so tiny and huge directions
// normalize without underflow or overflow.
RhNode rh_leaf(vec3 origin, vec3 direction) {
    const float m = rh_max_abs(direction);
    if (!rh_finite(origin) || !rh_finite(direction) || !(m > 0.0)) return rh_empty_node();
    return RhNode(vec4(origin, 0.0), vec4(normalize(direction / m), 0.0));
}

// The angle between two unit vectors, accurate near 0 and pi (atan of |a x b| and a . b, not acos).
float rh_angle(vec3 a, vec3 b) { return atan(length(cross(a, b)), dot(a, b)); }

// The union of up to 16 children (RhNode kids[16], the first `count` used; empty ones skipped):
//  - sphere: centre = middle of the box of the children's centres; radius = max |c_i - c| + r_i (triangle
//    inequality: every origin within r_i of c_i is within that of c);
//  - cone: axis = normalized sum of the children's axes (the first child's axis if the sum is zero, e.g. two opposite
//    rays); spread = max angle(axis, a_i) + spread_i. This holds for ANY axis (triangle inequality of angles on the
//    sphere), so opposite directions merely give a spread of pi or more, which means every direction.
// Identical rays give radius 0 (plus the padding) and spread 0; a single child gives itself padded; a last node with
// fewer than B children (counts that are not a power of B) uses just those.
// Both are then padded by RH_PAD relatively (plus RH_PAD of the coordinates' size for the rounding of c_i - c), so
// the float rounding of these few operations can only make a node larger than the exact union.
RhNode rh_union(RhNode kids[16], uint count) {
    // BEGIN EXERCISE 04.node_union: bound the non-empty children (sphere.w >= 0): a sphere holding every child's
    // sphere and a cone holding every child's cone (axis: their normalized axis sum; spread: the largest angle to a
    // child's axis plus its spread), both padded by RH_PAD; every direction when the spread reaches
    // RH_ALL_DIRECTIONS. rh_empty_node() when no child has rays.
    vec3 lo = vec3(RT_INFINITY), hi = vec3(-RT_INFINITY), axis_sum = vec3(0.0), first_axis = vec3(1.0, 0.0, 0.0);
    bool any = false, all_directions = false;
    for (uint i = 0u; i < count; ++i) {
        if (!(kids[i].sphere.w >= 0.0)) continue;
        if (!any) first_axis = kids[i].cone.xyz;
        any = true;
        lo = min(lo, kids[i].sphere.xyz);
        hi = max(hi, kids[i].sphere.xyz);
        axis_sum += kids[i].cone.xyz;
        all_directions = all_directions || kids[i].cone.w >= RH_ALL_DIRECTIONS;
    }
    if (!any) return rh_empty_node();
    const vec3 c = 0.5 * lo + 0.5 * hi;   // not (lo + hi) / 2: no overflow for huge coordinates
    const float len = length(axis_sum);
    const vec3 axis = (len > 0.0 && rt_isfinite(len)) ? axis_sum / len : first_axis;
    float radius = 0.0, spread = 0.0;
    for (uint i = 0u; i < count; ++i) {
        if (!(kids[i].sphere.w >= 0.0)) continue;
        radius = max(radius, length(kids[i].sphere.xyz - c) + kids[i].sphere.w);
        spread = max(spread, rh_angle(axis, kids[i].cone.xyz) + kids[i].cone.w);
    }
    radius = radius * (1.0 + RH_PAD) + RH_PAD * max(rh_max_abs(c), rh_max_abs(hi - lo)) + 1e-30;
    spread = spread * (1.0 + RH_PAD) + RH_PAD;
    if (all_directions || !(spread < RH_ALL_DIRECTIONS)) spread = 3.14159274;   // every direction (also NaN)
    return RhNode(vec4(c, radius), vec4(axis, spread));
    // STUB: return count > 0u ? kids[0] : rh_empty_node();
    // END EXERCISE
}

// A triangle's bounding sphere: the middle of its box, and the largest distance to a vertex, padded as above so that
// it also holds every point the exact ray/triangle test may report a hit at (that test's rounding is a few ulps of
// the coordinates, covered by RH_PAD times their size).
vec4 rh_triangle_sphere(vec3 a, vec3 b, vec3 c) {
    const vec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
    const vec3 m = 0.5 * lo + 0.5 * hi;
    const float r = max(length(a - m), max(length(b - m), length(c - m)));
    return vec4(m, r * (1.0 + RH_PAD) + RH_PAD * max(rh_max_abs(m), rh_max_abs(hi - lo)) + 1e-30);
}

// Can some ray of the node hit something inside sphere s? Every ray is o + t d with |o - c| <= r and d within the
// cone, so its points lie in the sphere (c, r) swept along the cone K: within r of c + K. The sphere s is out of
// reach when the distance from q = s.centre - c to K exceeds r + s.radius. For q at angle phi from the axis and a
// spread theta, that distance is 0 when phi <= theta, |q| when phi - theta >= 90 degrees (the apex is closest), and
// |q| sin(phi - theta) between; with A = q . axis = |q| cos(phi) and B = |q x axis| = |q| sin(phi), no acos is
// needed: |q| sin(phi - theta) = B cos(theta) - A sin(theta), |q| cos(phi - theta) = A cos(theta) + B sin(theta).
// Rejects only when every comparison says so: NaN or overflow (huge coordinates) keep the pair.
bool rh_may_hit(RhNode node, vec4 s) {
    if (!(node.sphere.w >= 0.0)) return false;   // empty node: no ray to test
    // BEGIN EXERCISE 04.cone_sphere_test: true unless the distance from s's centre to the node's sphere swept along
    // its cone exceeds the two radii (plus a rounding margin); a node covering every direction reaches everything.
    if (node.cone.w >= RH_ALL_DIRECTIONS) {
        // Every direction: the rays reach everything (the origins' sphere is then the only bound, and it does not
        // limit where a ray can go). Keep the pair.
        return true;
    }
    const vec3 q = s.xyz - node.sphere.xyz;
    const float q_len = length(q);
    const float reach = node.sphere.w + s.w;
    const float margin = RH_PAD * (q_len + reach + rh_max_abs(node.sphere.xyz) + rh_max_abs(s.xyz));
    const float A = dot(q, node.cone.xyz);
    const float B = length(cross(q, node.cone.xyz));
    const float ct = cos(node.cone.w), st = sin(node.cone.w);
    const float sin_part = B * ct - A * st;   // |q| sin(phi - theta)
    const float cos_part = A * ct + B * st;   // |q| cos(phi - theta)
    const float dist = cos_part <= 0.0 ? q_len : sin_part;
    const bool far = sin_part > 0.0 && dist > reach + margin;
    return !far;
    // STUB: return false;
    // END EXERCISE
}

// ---------------------------------------------------------------------------------------------------------------
// The pairs of the traversal (object_tree.h): uvec2(ray side, object side).
//  - ray side: level << 27 | index on that level (level 0: the ray's index in its group; l >= 1: a node);
//  - object side: RH_TRIANGLE_FLAG | triangle id, or the index of an object node.
#define RH_TRIANGLE_FLAG 0x80000000u
#define RH_RAY_INDEX_BITS 27u
#define RH_RAY_INDEX_MASK 0x07ffffffu

uint rh_ray_level(uint x) { return x >> RH_RAY_INDEX_BITS; }
uint rh_ray_index(uint x) { return x & RH_RAY_INDEX_MASK; }
uint rh_ray_side(uint level, uint index) { return level << RH_RAY_INDEX_BITS | index; }
bool rh_is_triangle(uint y) { return (y & RH_TRIANGLE_FLAG) != 0u; }

// The cheap per-ray test before the exact one (object_tree.cpp: rh_ray_may_hit): rh_may_hit for a single ray
// (spread 0: no trigonometry), and the ray's length (a sphere farther than tmax |d| is out of reach).
bool rh_ray_may_hit(vec3 origin, vec3 direction, float tmax, vec4 s) {
    const float m = rh_max_abs(direction);
    if (!rh_finite(origin) || !rh_finite(direction) || !(m > 0.0)) return false;
    // BEGIN EXERCISE 04.cone_sphere_test: the single-ray form: rh_may_hit for a node of one ray (spread 0, so no
    // trigonometry), and the sphere out of reach when its nearest point lies beyond tmax.
    const vec3 axis = normalize(direction / m);
    const vec3 q = s.xyz - origin;
    const float q_len = length(q);
    const float margin = RH_PAD * (q_len + s.w + rh_max_abs(origin) + rh_max_abs(s.xyz));
    const float A = dot(q, axis);
    const float B = length(cross(q, axis));
    const float dist = A <= 0.0 ? q_len : B;
    if (dist > s.w + margin) return false;   // A <= 0: the origin is the ray's nearest point to the centre
    const float len = m * length(direction / m);   // |d| without overflow or underflow
    return !(q_len - s.w - margin > tmax * len * (1.0 + RH_PAD));
    // STUB: return true;
    // END EXERCISE
}

// The second cheap test (object_tree.cpp: rh_ray_box_test): can the ray pass through the box [lo, hi] for some
// 0 < t <= tmax? The slab test (Kay & Kajiya 1986), the box padded as the sphere is; a NaN tmax keeps the pair.
// `precise`: evaluated as written in every shader (no fused or reordered operations), so an object node's test in
// rh_cull.comp keeps every ray its triangles' tests in rh_leaf.comp keep (each step is monotone in the box).
bool rh_ray_box_test(vec3 origin, vec3 direction, float tmax, vec3 lo, vec3 hi) {
    if (!rh_finite(origin) || !rh_finite(direction) || !(rh_max_abs(direction) > 0.0)) return false;
    precise float pad = RH_PAD * (rh_max_abs(origin) + max(rh_max_abs(lo), rh_max_abs(hi))) + 1e-30;
    precise float t_in = 0.0, t_out = rt_isfinite(tmax) ? tmax : RT_INFINITY;
    for (int i = 0; i < 3; ++i) {
        precise float near = lo[i] - pad - origin[i], far = hi[i] + pad - origin[i];   // the slab, from the origin
        if (direction[i] == 0.0) {   // parallel to the slab: inside it for every t, or for none
            if (near > 0.0 || far < 0.0) return false;
            continue;
        }
        precise float t_a = near / direction[i], t_b = far / direction[i];
        t_in = max(t_in, min(t_a, t_b));
        t_out = min(t_out, max(t_a, t_b));
    }
    precise float t_end = t_out * (1.0 + RH_PAD) + 1e-30;
    return !(t_in > t_end);   // a NaN keeps the pair
}

// Can some ray of the node pass through the box [lo, hi]? (object_tree.cpp: rh_node_box_test.) The slab test of
// rh_ray_box_test in interval arithmetic over all the node's rays at once (as for ray packets: Boulos et al. 2006,
// "Geometric and arithmetic culling methods for entire ray packets"). On axis i:
//  - every origin lies in [c_i - r, c_i + r];
//  - a unit direction d within the cone has d_i = cos(angle(d, e_i)), and that angle is within the spread theta of
//    the axis' angle alpha_i to e_i (cos alpha_i = a_i, sin alpha_i = |a with a_i zeroed|), so d_i lies in
//    [cos(min(alpha_i + theta, pi)), cos(max(alpha_i - theta, 0))]: a_i cos(theta) -/+ sin(alpha_i) sin(theta), or
//    -1 / 1 when the cone passes the axis' direction (no acos needed);
//  - so a ray's point o_i + t d_i (t >= 0) lies in [c_i - r + t d_lo, c_i + r + t d_hi], which reaches the slab
//    [lo_i, hi_i] when t d_lo <= hi_i - (c_i - r) and t d_hi >= lo_i - (c_i + r): each a half-line of t.
// The box is out of reach when the three axes' t intervals and t >= 0 do not overlap (the node has no tmax). The
// cone+sphere test (rh_may_hit) bounds a large or thin triangle by a sphere half its longest side wide; its box is
// what the leaves' per-ray test culls with, and this test lets a node cull with it before its rays are split
// (BoxAnimated: 34 leaf pairs a shadow ray, 5 with it). Padded like rh_ray_box_test, the directions' bounds by RH_PAD
// absolutely (they are at most 1; GPU sin and cos are good to about 1e-6), and a bound of 0 moved off 0 outwards, so
// no division is by 0. Rejects only when every comparison says so: NaN or overflow keep the pair.
bool rh_node_box_test(RhNode node, vec3 lo, vec3 hi) {
    if (!(node.sphere.w >= 0.0)) return false;   // empty node: no ray to test
    if (node.cone.w >= RH_ALL_DIRECTIONS) return true;
    const vec3 c = node.sphere.xyz, a = node.cone.xyz;
    const float r = node.sphere.w, ct = cos(node.cone.w), st = sin(node.cone.w);
    const vec3 sin_alpha = sqrt(vec3(a.y * a.y + a.z * a.z, a.z * a.z + a.x * a.x, a.x * a.x + a.y * a.y));
    vec3 d_hi = mix(vec3(1.0), a * ct + sin_alpha * st, lessThanEqual(a, vec3(ct))) + RH_PAD;
    vec3 d_lo = mix(vec3(-1.0), a * ct - sin_alpha * st, greaterThanEqual(a, vec3(-ct))) - RH_PAD;
    d_hi = mix(d_hi, vec3(1e-30), equal(d_hi, vec3(0.0)));
    d_lo = mix(d_lo, vec3(-1e-30), equal(d_lo, vec3(0.0)));
    precise float pad = RH_PAD * (rh_max_abs(c) + r + max(rh_max_abs(lo), rh_max_abs(hi))) + 1e-30;
    precise vec3 t_lo = (hi + pad - (c - r)) / d_lo;   // where the rays' lowest point crosses the slab's top
    precise vec3 t_hi = (lo - pad - (c + r)) / d_hi;   // where their highest point crosses its bottom
    // A positive bound ends the half-line (t <= ...), a negative one starts it (t >= ...).
    const vec3 zero = vec3(0.0), none = vec3(RT_INFINITY);
    precise vec3 enter = max(mix(-none, t_lo, lessThan(d_lo, zero)), mix(-none, t_hi, greaterThan(d_hi, zero)));
    precise vec3 leave = min(mix(none, t_lo, greaterThan(d_lo, zero)), mix(none, t_hi, lessThan(d_hi, zero)));
    precise float t_in = max(0.0, max(enter.x, max(enter.y, enter.z)));
    precise float t_end = min(leave.x, min(leave.y, leave.z)) * (1.0 + RH_PAD) + 1e-30;
    return !(t_in > t_end);   // a NaN keeps the pair
}

// The ray against triangle (a, b, c)'s box (object_tree.cpp: rh_ray_box_may_hit).
bool rh_ray_box_may_hit(vec3 origin, vec3 direction, float tmax, vec3 a, vec3 b, vec3 c) {
    return rh_ray_box_test(origin, direction, tmax, min(a, min(b, c)), max(a, max(b, c)));
}

// --objects tree: split the rays of a surviving pair when their beam is wider than a quarter of the object node's
// radius where it meets it, else the object node (object_tree.h: rh_split_rays and kSplitRaysWidth, why a quarter).
// Either choice is exact.
#define RH_SPLIT_RAYS_WIDTH 0.25   // object_tree.h: kSplitRaysWidth
bool rh_split_rays(RhNode node, vec4 s) {
    if (node.cone.w >= RH_ALL_DIRECTIONS) return true;
    const float distance = length(s.xyz - node.sphere.xyz);
    const float width = node.sphere.w + distance * sin(min(node.cone.w, 1.57079637));
    return width > RH_SPLIT_RAYS_WIDTH * s.w;
}
