// The scene's vertex positions only (scene.glsl's ScenePositions, same binding and layout): the stage's passes
// include this instead of scene.glsl, whose other six buffers would count against the 16 storage blocks a compute
// shader may use (Mesa and NVIDIA), next to the pipeline's own (wavefront.glsl) and the stage's.
layout(std430, binding = RT_BINDING_POSITIONS) readonly buffer ScenePositions { vec4 rt_positions[]; };

void rh_load_triangle(uint triangle, out vec3 a, out vec3 b, out vec3 c) {
    a = rt_positions[3u * triangle].xyz;
    b = rt_positions[3u * triangle + 1u].xyz;
    c = rt_positions[3u * triangle + 2u].xyz;
}
