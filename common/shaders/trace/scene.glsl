// The scene on the GPU, as GpuScene (common/gpu/pipeline/gpu_scene.h) uploads it once per frame: the same triangle
// soup, materials, lights, textures and camera as rt::Scene. Layouts here and in gpu_scene.h must stay equal (a unit
// test checks the struct sizes and offsets). Define RT_SCENE_WRITABLE before including to drop the readonly qualifiers.
#include "common/shaders/bindings.glsl"
#include "camera.glsl"

#ifdef RT_SCENE_WRITABLE
#define RT_SCENE_ACCESS
#else
#define RT_SCENE_ACCESS readonly
#endif

#define RT_LIGHT_POINT 0
#define RT_LIGHT_SPOT 1
#define RT_LIGHT_DIRECTIONAL 2

#define RT_ALPHA_OPAQUE 0
#define RT_ALPHA_MASK 1
#define RT_ALPHA_BLEND 2

struct Material {                    // 160 bytes, std430 (GpuMaterial)
    vec4 base_color;
    vec3 emissive;       int base_color_texture;   // textures: -1 = none
    vec3 specular_color; float metallic;
    float roughness; float transmission; float ior; float specular;
    vec3 attenuation;    float thickness;          // attenuation = sigma_a per channel (0: no absorption)
    int normal_texture;  float normal_scale;  int alpha_mode;  float alpha_cutoff;   // alpha: RT_ALPHA_*, the alpha test's threshold
    int metallic_roughness_texture; int emissive_texture; int transmission_texture; int material_pad1;
    vec4 base_color_uv_matrix;                     // KHR_texture_transform (rt::uv_matrix): a, b, c, d
    vec4 normal_uv_matrix;
    vec2 base_color_uv_offset; vec2 normal_uv_offset;
};

struct Light {                       // 64 bytes, std430 (GpuLight)
    vec3 color;     int type;
    vec3 position;  float intensity;
    vec3 direction; float range;
    float inner_cone; float outer_cone;
    float cos_inner; float cos_outer;              // std::cos of the cones, computed on the CPU
};

struct TextureInfo {                 // 16 bytes (GpuTextureInfo): texel (x, y) is word first + y * width + x
    int width; int height; int sampler; uint first;   // sampler: bit 0 nearest, bits 1-2 wrap_s, bits 3-4 wrap_t
};

// Triangle i uses entries 3i, 3i+1, 3i+2. RT_SCENE_MATERIALS_ONLY (opacity.glsl in a traversal's pass, which must
// stay within 16 storage blocks) leaves out the positions, normals and lights and what reads them.
#ifndef RT_SCENE_MATERIALS_ONLY
layout(std430, binding = RT_BINDING_POSITIONS) RT_SCENE_ACCESS buffer ScenePositions { vec4 rt_positions[]; };
// With normal maps, vertex i's tangent (xyz, w = handedness) is rt_normals[3 * rt_triangle_count + i].
layout(std430, binding = RT_BINDING_NORMALS) RT_SCENE_ACCESS buffer SceneNormals { vec4 rt_normals[]; };
#endif
// With vertex colours (RT_VERTEX_COLORS), vertex i's RGBA is rt_uvs[3 * rt_triangle_count + 2i] and [... + 2i + 1].
layout(std430, binding = RT_BINDING_UVS) RT_SCENE_ACCESS buffer SceneUvs { vec2 rt_uvs[]; };
layout(std430, binding = RT_BINDING_MATERIAL_IDS) RT_SCENE_ACCESS buffer SceneMaterialIds { uint rt_material_ids[]; };
layout(std430, binding = RT_BINDING_MATERIALS) RT_SCENE_ACCESS buffer SceneMaterials { Material rt_materials[]; };
#ifndef RT_SCENE_MATERIALS_ONLY
layout(std430, binding = RT_BINDING_LIGHTS) RT_SCENE_ACCESS buffer SceneLights { Light rt_lights[]; };
#endif
// The area lights' buffer is declared in area_light.glsl, which only the shade pass includes: Mesa counts every
// declared storage block against the 16 a compute shader may use, read or not.
// sRGB decode and alpha tables (the exact floats the C++ sample_texture uses), then the textures, unpadded: words
// [0, 4 * rt_texture_count) hold one TextureInfo per texture, the rest every texture's texels one after the other
// (one uint per texel: the file's RGBA8 bytes r, g, b, a from the low byte up; row 0 = top of the image = v 0).
// Memory is the sum of the texture sizes, whatever their mix (GpuScene::upload_textures).
layout(std430, binding = RT_BINDING_TEXTURE_INFO) readonly buffer SceneTextures {
    float rt_srgb_lut[256];
    float rt_alpha_lut[256];
    uint rt_texture_words[];
};

layout(std140, binding = RT_UBO_SCENE) uniform SceneBlock {   // 128 bytes (GpuSceneBlock)
    Camera rt_camera;
    vec3 rt_background; uint rt_triangle_count;
    uint rt_material_count; uint rt_light_count; uint rt_texture_count; uint rt_area_light_count;   // lights: punctual
    vec2 rt_environment_rotation; vec2 rt_environment_pad;   // environment.glsl (cos, sin of --environment-rotation)
};

TextureInfo rt_texture_info(int texture) {
    const uint i = 4u * uint(texture);
    return TextureInfo(int(rt_texture_words[i]), int(rt_texture_words[i + 1u]), int(rt_texture_words[i + 2u]),
                       rt_texture_words[i + 3u]);
}

// The RGBA8 bytes of texel (x, y) of a texture, 0 <= x < width, 0 <= y < height.
uvec4 rt_texel_bytes(TextureInfo info, int x, int y) {
    const uint w = rt_texture_words[info.first + uint(y) * uint(info.width) + uint(x)];
    return uvec4(w & 0xffu, (w >> 8) & 0xffu, (w >> 16) & 0xffu, w >> 24);
}

#ifdef RT_VERTEX_COLORS
// The vertex colour (COLOR_0) at barycentrics (u, v) of a triangle: c0 + u (c1 - c0) + v (c2 - c0), exactly c0 on
// a triangle of one colour (rt::vertex_color, common/trace/opacity.h).
vec4 rt_vertex_color(uint triangle, float u, float v) {
    const uint c = 3u * rt_triangle_count + 6u * triangle;
    const vec4 c0 = vec4(rt_uvs[c], rt_uvs[c + 1u]), c1 = vec4(rt_uvs[c + 2u], rt_uvs[c + 3u]);
    const vec4 c2 = vec4(rt_uvs[c + 4u], rt_uvs[c + 5u]);
    precise vec4 color = c0 + u * (c1 - c0) + v * (c2 - c0);
    return color;
}
#endif

#ifndef RT_SCENE_MATERIALS_ONLY
void load_triangle(uint triangle, out vec3 a, out vec3 b, out vec3 c) {
    a = rt_positions[3u * triangle].xyz;
    b = rt_positions[3u * triangle + 1u].xyz;
    c = rt_positions[3u * triangle + 2u].xyz;
}

// Twin of rt::SurfacePoint / rt::surface_point (common/trace/whitted.h), float geometry.
struct SurfacePoint {
    vec3 position;          // interpolated from the vertices
    vec3 geometric_normal;  // unit, facing the incoming ray
    vec3 shading_normal;    // unit, on the same side as geometric_normal
    vec2 uv;
    vec4 color;             // the vertex colour (COLOR_0), white without RT_VERTEX_COLORS
    bool front_face;
    uint material;
};

SurfacePoint surface_point(Ray ray, uint triangle, float u, float v) {
    const uint i = 3u * triangle;
    const vec3 a = rt_positions[i].xyz, b = rt_positions[i + 1u].xyz, c = rt_positions[i + 2u].xyz;
    precise float w = 1.0 - u - v;
    SurfacePoint s;
    precise vec3 position = w * a + u * b + v * c;
    s.position = position;
    precise vec3 ba = b - a, ca = c - a;
    vec3 ng = rt_cross(ba, ca);
    const float len = rt_length(ng);
    precise vec3 ng_unit = ng / len;
    ng = len > 0.0 ? ng_unit : -ray.direction;
    s.front_face = rt_dot(ng, ray.direction) < 0.0;
    s.geometric_normal = s.front_face ? ng : -ng;
    precise vec3 ns = w * rt_normals[i].xyz + u * rt_normals[i + 1u].xyz + v * rt_normals[i + 2u].xyz;
    const float ns_len = rt_length(ns);
    precise vec3 ns_unit = ns / ns_len;
    ns = (ns_len > 0.0 && rt_isfinite(ns_len)) ? ns_unit : s.geometric_normal;
    s.shading_normal = rt_dot(ns, s.geometric_normal) < 0.0 ? -ns : ns;
    precise vec2 uv = w * rt_uvs[i] + u * rt_uvs[i + 1u] + v * rt_uvs[i + 2u];
    s.uv = uv;
#ifdef RT_VERTEX_COLORS
    s.color = rt_vertex_color(triangle, u, v);
#else
    s.color = vec4(1.0);
#endif
    s.material = rt_material_ids[triangle];
    return s;
}
#endif
