#version 450 core
// After rh_heads.comp and the compaction that lists the group starts: one list the CPU reads in a single read-back,
// [count, then per group its first ray and its ray kind], so no ray is read back to learn its group's kind.
#include "rh_common.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_COUNTS) readonly buffer Heads { uint rh_heads[]; };
layout(std430, binding = RH_BINDING_OFFSETS) readonly buffer HeadCount { uint rh_head_count; };
layout(std430, binding = RH_BINDING_PAIRS_OUT) writeonly buffer Groups { uint rh_groups[]; };

void main() {
    const uint i = rt_global_index();
    if (i == 0u) rh_groups[0] = rh_head_count;
    if (i >= rh_head_count || i >= wf_input_count) return;
    const uint head = rh_heads[i];
    rh_groups[1u + 2u * i] = head;
    rh_groups[2u + 2u * i] = wf_kind(wf_rays_in[wf_input_first + head]);
}
