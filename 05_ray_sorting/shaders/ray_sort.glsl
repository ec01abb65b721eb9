// Shared by the ray-sorting passes (ray_sort.h): bindings, the queued ray's layout, and the ray key.
//
// Bindings: the sorting passes (keys, compression, decompression) are a primitive like the scan and the radix sort
// they call, and reuse the primitives' points 8..14 (bindings.glsl), which every primitive rebinds for each call, so
// sorting disturbs neither the scene (0..7) nor the wavefront pipeline (16..23). The gather and scatter passes move
// the pipeline's own rays and results, so they bind as a stage does: from the traversal's first point (24; stage 04
// rebinds its buffers there before each of its passes).
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"

#define RS_BINDING_0 RT_BINDING_SCAN_IN
#define RS_BINDING_1 RT_BINDING_SCAN_OUT
#define RS_BINDING_2 RT_BINDING_SCAN_SUMS
#define RS_BINDING_3 RT_BINDING_COMPACT_FLAGS
#define RS_BINDING_4 RT_BINDING_COMPACT_OFFSETS
#define RS_BINDING_5 RT_BINDING_COMPACT_VALUES
#define RS_BINDING_6 RT_BINDING_COMPACT_OUT
#define RS_STAGE_BINDING_0 (RT_BINDING_STAGE_FIRST + 8)
#define RS_STAGE_BINDING_1 (RT_BINDING_STAGE_FIRST + 9)
#define RS_STAGE_BINDING_2 (RT_BINDING_STAGE_FIRST + 10)

// WavefrontRay (common/shaders/wavefront/wavefront.glsl), 64 bytes std430; only what the key reads is named.
struct RsRay {
    vec3 origin; float tmax;
    vec3 direction; uint pixel;
    vec3 weight; uint depth_kind;   // depth | kind << 16
    uint path; uint light; uint pad0; uint pad1;
};

// The key's layout (RayKeyLayout in ray_keys.h, which sets these uniforms and documents the mapping).
uniform vec3 rs_box_min;
uniform float rs_origin_scale;     // cells per unit, the same on every axis: the cells are cubes
uniform uvec3 rs_origin_bits;      // bits of each axis' cell index (0 for a flat axis)
uniform uint rs_origin_total;      // rs_origin_bits.x + .y + .z
uniform uvec2 rs_direction_bits;   // bits of the octahedral u and v cells
uniform uint rs_direction_total;   // rs_direction_bits.x + rs_direction_bits.y
uniform uint rs_hash_drop;         // low hash bits given up so the group fits in 32 bits
uniform uint rs_hash_bits;         // hash bits kept (above them: the group)
uniform uint rs_group_count;       // 3 + lights
uniform uint rs_direction_major;   // 1: the direction cell above the origin cell (reflection, refraction)

// ray_keys.cpp: quantize_axis. Cell of one origin coordinate in the virtual grid; outside the box clamps.
uint rs_quantize_axis(float o, float box_min, float scale, uint bits) {
    if (bits == 0u) return 0u;
    precise float f = (o - box_min) * scale;
    const uint cells = 1u << bits;
    if (!(f >= 0.0)) return 0u;
    if (f >= float(cells)) return cells - 1u;
    return uint(f);
}

// ray_keys.cpp: octahedral_cell. Largest c < 2^bits with n >= (-1 + c 2^(1 - bits)) s, i.e. the cell of n / s in
// [-1, 1], found bit by bit without a division (so the CPU gets the same cell bit for bit).
uint rs_octahedral_cell(float n, float s, uint bits) {
    uint c = 0u;
    for (int bit = int(bits) - 1; bit >= 0; --bit) {
        const uint t = c | (1u << uint(bit));
        precise float threshold = ldexp(float(t), 1 - int(bits)) - 1.0;
        precise float limit = threshold * s;
        if (n >= limit) c = t;
    }
    return c;
}

// x << s, 0 when s >= 32 (GLSL leaves shifts by 32 undefined).
uint rs_shift_left(uint x, uint s) { return s >= 32u ? 0u : x << s; }

// Appends the bits of the cells, most significant level first, one bit of each axis per level (Morton order).
uint rs_interleave3(uvec3 c, uvec3 bits) {
    uint code = 0u;
    const uint levels = max(bits.x, max(bits.y, bits.z));
    for (uint level = levels; level-- > 0u;)
        for (uint a = 0u; a < 3u; ++a)
            if (level < bits[a]) code = (code << 1u) | ((c[a] >> level) & 1u);
    return code;
}

uint rs_group(RsRay r) {
    const uint kind = r.depth_kind >> 16;
    const uint group = kind == 1u ? 3u + r.light : (kind == 0u ? 0u : kind - 1u);
    return min(group, rs_group_count - 1u);
}

uint rs_ray_key(RsRay r) {
    // BEGIN EXERCISE 05.ray_key: quantize the origin in the virtual grid of cubic cells (rs_quantize_axis per
    // axis, the one scale rs_origin_scale on all three, each axis its own bits) and the direction by the octahedral
    // map (d / (|dx| + |dy| + |dz|), the lower hemisphere folded; rs_octahedral_cell), interleave each
    // (rs_interleave3), put the direction code above the origin code (rs_direction_major: reflection and refraction
    // rays, a coarse direction cell) or below it (shadow rays), keep the top bits, and the ray's group (rs_group)
    // above them all. Must equal ray_keys.cpp's key bit for bit.
    const uvec3 oc = uvec3(rs_quantize_axis(r.origin.x, rs_box_min.x, rs_origin_scale, rs_origin_bits.x),
                           rs_quantize_axis(r.origin.y, rs_box_min.y, rs_origin_scale, rs_origin_bits.y),
                           rs_quantize_axis(r.origin.z, rs_box_min.z, rs_origin_scale, rs_origin_bits.z));
    const vec3 d = r.direction;
    precise float s = (abs(d.x) + abs(d.y)) + abs(d.z);
    precise float nu = d.x;
    precise float nv = d.y;
    if (d.z < 0.0) {   // the lower hemisphere folds over the diamond's edges
        nu = (s - abs(d.y)) * (d.x >= 0.0 ? 1.0 : -1.0);
        nv = (s - abs(d.x)) * (d.y >= 0.0 ? 1.0 : -1.0);
    }
    const uvec3 dc = uvec3(rs_octahedral_cell(nu, s, rs_direction_bits.x), rs_octahedral_cell(nv, s, rs_direction_bits.y), 0u);
    const uint origin_code = rs_interleave3(oc, rs_origin_bits);
    const uint direction_code = rs_interleave3(dc, uvec3(rs_direction_bits, 0u));
    const uint hash = rs_direction_major != 0u
                          ? rs_shift_left(direction_code, rs_origin_total) | origin_code
                          : rs_shift_left(origin_code, rs_direction_total) | direction_code;
    const uint kept = rs_hash_drop >= 32u ? 0u : hash >> rs_hash_drop;
    return rs_shift_left(rs_group(r), rs_hash_bits) | kept;
    // STUB: return rs_shift_left(rs_group(r), rs_hash_bits);
    // END EXERCISE
}
