// The scene on the GPU: rt::Scene uploaded as SSBOs (plus a UBO), in one layout that stages
// 02-05 all read through common/shaders/trace/scene.glsl. Upload once per frame (or once, for a still scene), then
// bind() before the passes; the bindings are in bindings.h / bindings.glsl.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "common/scene/scene.h"
#include "common/gpu/gl/buffer.h"
#include "environment_texture.h"

namespace rt::gpu {

// std430 / std140 mirrors of the GLSL structs in scene.glsl and camera.glsl (vec3 + scalar pairs fill 16 bytes).
struct GpuCamera {                       // camera.glsl: Camera
    glm::vec3 position; std::int32_t projection;
    glm::vec3 right;    float tan_half_fov;   // std::tan(yfov * 0.5f), as rt::camera_ray computes it
    glm::vec3 up;       float aspect;
    glm::vec3 forward;  float xmag;
    float ymag, znear, zfar, yfov;
};
static_assert(sizeof(GpuCamera) == 80);

struct GpuMaterial {                     // scene.glsl: Material
    glm::vec4 base_color;
    glm::vec3 emissive;       std::int32_t base_color_texture;
    glm::vec3 specular_color; float metallic;
    float roughness, transmission, ior, specular;
    glm::vec3 attenuation;    float thickness;          // attenuation = sigma_a (rt::absorption_coefficient)
    std::int32_t normal_texture; float normal_scale; std::int32_t alpha_mode; float alpha_cutoff;   // alpha: AlphaMode, alpha_test_cutoff (opacity.h)
    std::int32_t metallic_roughness_texture, emissive_texture, transmission_texture, material_pad1;
    // KHR_texture_transform: rt::uv_matrix (a, b, c, d) and the offsets of the base colour and normal textures.
    glm::vec4 base_color_uv_matrix;
    glm::vec4 normal_uv_matrix;
    glm::vec2 base_color_uv_offset; glm::vec2 normal_uv_offset;
};
static_assert(sizeof(GpuMaterial) == 160);

struct GpuLight {                        // scene.glsl: Light
    glm::vec3 color;     std::int32_t type;
    glm::vec3 position;  float intensity;
    glm::vec3 direction; float range;
    float inner_cone, outer_cone;
    float cos_inner, cos_outer;          // std::cos(inner_cone), std::cos(outer_cone), as light_incidence has them
};
static_assert(sizeof(GpuLight) == 64);

// An area light (scene.glsl: rt_area_light), six vec4 of the area-light buffer; the running areas of the lights that
// are not parallelograms follow the lights, one float each (AreaLight::cdf_first indexes them).
struct GpuAreaLight {
    glm::vec3 corner;  float area;
    glm::vec3 edge_u;  std::uint32_t first_triangle;
    glm::vec3 edge_v;  std::uint32_t triangle_count;
    glm::vec2 uv_corner, uv_edge_u;
    glm::vec2 uv_edge_v; std::uint32_t material, flags;   // flags: kAreaLightParallelogram | kAreaLightTwoSided
    std::uint32_t cdf_first, pad[3];
};
static_assert(sizeof(GpuAreaLight) == 96);
constexpr std::uint32_t kAreaLightParallelogram = 1, kAreaLightTwoSided = 2;

struct GpuTextureInfo {                  // scene.glsl: TextureInfo
    std::int32_t width, height;
    std::int32_t sampler;                // bit 0: nearest; bits 1-2: wrap_s, bits 3-4: wrap_t (rt::Wrap)
    std::uint32_t first;                 // index of texel (0, 0) in the texture words (rt_texture_words)
};
static_assert(sizeof(GpuTextureInfo) == 16);

struct GpuSceneBlock {                   // scene.glsl: uniform SceneBlock (std140)
    GpuCamera camera;
    glm::vec3 background; std::uint32_t triangle_count;
    std::uint32_t material_count, light_count, texture_count, area_light_count;   // light_count: punctual
    glm::vec2 environment_rotation;      // Environment::rotation (cos, sin); read only with RT_ENVIRONMENT
    glm::vec2 environment_pad;
};
static_assert(sizeof(GpuSceneBlock) == 128);

GpuCamera to_gpu(const Camera& camera);
GpuMaterial to_gpu(const Material& material);
GpuLight to_gpu(const Light& light);
GpuAreaLight to_gpu(const AreaLight& light);

class GpuScene {
public:
    // Uploads everything (buffers are reallocated only when their sizes change), except for a still scene already
    // here (the same nonzero Scene::still_id as the last upload): then only the scene block (camera, background).
    // Returns the bytes of the scene itself it sent (0 for a resident one), not counting the scene block. Needs a
    // current context. Throws SceneError (one line naming the size and the limit: the stages exit 2) when the
    // textures do not fit one shader storage block (GL_MAX_SHADER_STORAGE_BLOCK_SIZE).
    std::size_t upload(const Scene& scene);
    // Only the camera and background (a camera animation over a still scene).
    void upload_camera(const Camera& camera, const glm::vec3& background);
    // Binds every SSBO and the scene UBO at their binding points.
    void bind() const;

    std::size_t triangle_count() const { return block_.triangle_count; }
    // Lights in the one numbering of shadow rays: the punctual ones, then the area lights.
    std::size_t light_count() const { return std::size_t(block_.light_count) + block_.area_light_count; }
    std::size_t punctual_light_count() const { return block_.light_count; }
    std::size_t area_light_count() const { return block_.area_light_count; }
    std::size_t material_count() const { return block_.material_count; }
    std::size_t texture_count() const { return block_.texture_count; }
    // Whether the scene has an --environment map (then the passes are compiled with RT_ENVIRONMENT).
    bool has_environment() const { return environment_.present(); }
    bool has_vertex_colors() const { return vertex_colors_; }   // RT_VERTEX_COLORS (scene.glsl)
    const EnvironmentTexture& environment() const { return environment_; }
    // The scene's ambient model (the passes are compiled with RT_AMBIENT_NONE or RT_AMBIENT_HEMISPHERE for it).
    AmbientModel ambient() const { return ambient_; }
    const GpuSceneBlock& block() const { return block_; }
    // Bytes of GPU memory the scene takes.
    std::size_t bytes() const;
    // Of which the textures: sRGB tables, one GpuTextureInfo and width * height * 4 bytes per texture, no padding.
    std::size_t texture_bytes() const { return textures_.size(); }

    // The buffers, for stages that build on them (acceleration structures, a vertex pull in the rasterizer).
    const Buffer& positions() const { return positions_; }   // vec4 per vertex, 3 per triangle
    const Buffer& normals() const { return normals_; }
    const Buffer& uvs() const { return uvs_; }
    const Buffer& material_ids() const { return material_ids_; }
    const Buffer& materials() const { return materials_; }
    const Buffer& lights() const { return lights_; }
    const Buffer& textures() const { return textures_; }

private:
    void upload_textures(const Scene& scene);
    bool vertex_colors_ = false;
    Buffer positions_, normals_, uvs_, material_ids_, materials_, lights_, textures_, ubo_;
    Buffer area_lights_;   // empty without area lights
    EnvironmentTexture environment_;   // uploaded only when the scene's map changes
    GpuSceneBlock block_{};
    AmbientModel ambient_ = AmbientModel::Constant;
    std::uint64_t resident_id_ = 0;    // the still_id of the scene uploaded (0: none, or not still)
};

}  // namespace rt::gpu
