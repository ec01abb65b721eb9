#version 450 core
// One thread: the indirect dispatch arguments (work groups of 64) of a pass whose length only the GPU knows
// (rh_info[rh_slot]): the fold's select pass, over the hit list's length, with no read-back. (A traversal step's
// dispatch is written by the last work group of the step before: rh_cull.comp.)
#include "rh_common.glsl"
#include "rh_info.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = RH_BINDING_OFFSETS) writeonly buffer Args { uint rh_args[]; };

uniform uint rh_slot;        // rh_info index of the chunk's length
uniform uint rh_args_first;  // where its 3 arguments go

void main() {
    const uvec3 grid = rt_dispatch_size(rh_info[rh_slot], 64u);   // the passes' local size
    rh_args[rh_args_first] = grid.x;
    rh_args[rh_args_first + 1u] = grid.y;
    rh_args[rh_args_first + 2u] = grid.z;
}
