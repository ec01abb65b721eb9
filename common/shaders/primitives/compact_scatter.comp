#version 450 core
// Stream compaction, last step (flag -> scan -> scatter): element i with flags[i] != 0 goes to out[offsets[i]],
// where offsets is the exclusive scan of the flags. Writes the value (COMPACT_VALUES) or the index i.
#include "common/shaders/bindings.glsl"
#include "common/shaders/compute.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = RT_BINDING_COMPACT_FLAGS) readonly buffer Flags { uint flags[]; };
layout(std430, binding = RT_BINDING_COMPACT_OFFSETS) readonly buffer Offsets { uint offsets[]; };
#ifdef COMPACT_VALUES
layout(std430, binding = RT_BINDING_COMPACT_VALUES) readonly buffer Values { uint values[]; };
#endif
layout(std430, binding = RT_BINDING_COMPACT_OUT) writeonly buffer Out { uint compact_out[]; };

uniform uint n;

void main() {
    const uint i = rt_global_index();
    if (i >= n || flags[i] == 0u) return;
#ifdef COMPACT_VALUES
    compact_out[offsets[i]] = values[i];
#else
    compact_out[offsets[i]] = i;
#endif
}
