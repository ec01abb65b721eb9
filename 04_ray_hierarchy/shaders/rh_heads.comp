#version 450 core
// The groups of a queue: consecutive rays of one kind (and one light, for shadow rays) get one hierarchy each, so no
// node mixes groups. Flags ray i of the batch when it starts a group; a compaction lists the starts.
#include "rh_common.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = RH_BINDING_COUNTS) writeonly buffer Heads { uint rh_heads[]; };

uint group_key(WavefrontRay r) {
    const uint kind = wf_kind(r);
    return kind == WF_KIND_SHADOW ? 0x80000000u | r.light : kind;
}

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    const uint key = group_key(wf_rays_in[wf_input_first + i]);
    rh_heads[i] = (i == 0u || key != group_key(wf_rays_in[wf_input_first + i - 1u])) ? 1u : 0u;
}
