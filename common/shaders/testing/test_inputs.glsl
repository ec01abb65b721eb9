// For GLSL tests only (common/gpu/glsl_twins/*_test.cpp): read a Material and a Light from the test harness's input
// words, in the order the tests write them (GpuMaterial and GpuLight fields). Needs the harness's in_f/in_i/in_vec*.
#include "common/shaders/trace/shading.glsl"

Material in_material(uint k) {
    Material m;
    m.base_color = in_vec4(k); m.emissive = in_vec3(k + 4u); m.base_color_texture = in_i(k + 7u);
    m.specular_color = in_vec3(k + 8u); m.metallic = in_f(k + 11u);
    m.roughness = in_f(k + 12u); m.transmission = in_f(k + 13u); m.ior = in_f(k + 14u); m.specular = in_f(k + 15u);
    return m;
}

Light in_light(uint k) {
    Light l;
    l.color = in_vec3(k); l.type = in_i(k + 3u); l.position = in_vec3(k + 4u); l.intensity = in_f(k + 7u);
    l.direction = in_vec3(k + 8u); l.range = in_f(k + 11u); l.inner_cone = in_f(k + 12u);
    l.outer_cone = in_f(k + 13u); l.cos_inner = in_f(k + 14u); l.cos_outer = in_f(k + 15u);
    return l;
}
