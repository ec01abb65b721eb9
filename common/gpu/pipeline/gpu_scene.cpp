#include "gpu_scene.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "common/scene/gltf/gltf_io.h"
#include "common/trace/absorption.h"
#include "common/trace/opacity.h"
#include "common/trace/shading.h"
#include "common/trace/texture_transform.h"
#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/gl_counters.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt::gpu {

GpuCamera to_gpu(const Camera& c) {
    GpuCamera g{};
    g.position = c.position;
    g.projection = std::int32_t(c.projection);
    g.right = c.right;
    g.tan_half_fov = std::tan(c.yfov * 0.5f);   // = std::tan(T(cam.yfov) * T(0.5)) in rt::camera_ray<float>
    g.up = c.up;
    g.aspect = c.aspect;
    g.forward = c.forward;
    g.xmag = c.xmag;
    g.ymag = c.ymag;
    g.znear = c.znear;
    g.zfar = c.zfar;
    g.yfov = c.yfov;
    return g;
}

GpuMaterial to_gpu(const Material& m) {
    GpuMaterial g{};
    g.base_color = m.base_color;
    g.emissive = m.emissive;
    g.base_color_texture = m.base_color_texture;
    g.specular_color = m.specular_color;
    g.metallic = m.metallic;
    g.roughness = m.roughness;
    g.transmission = m.transmission;
    g.ior = m.ior;
    g.specular = m.specular;
    g.attenuation = absorption_coefficient(m);
    g.thickness = m.thickness;
    g.normal_texture = m.normal_texture;
    g.normal_scale = m.normal_scale;
    g.alpha_mode = int(m.alpha_mode);
    g.alpha_cutoff = alpha_test_cutoff(m);   // BLEND's 0.5 already chosen, as opacity.h does
    g.base_color_uv_matrix = uv_matrix(m.base_color_transform);
    g.normal_uv_matrix = uv_matrix(m.normal_transform);
    g.base_color_uv_offset = m.base_color_transform.offset;
    g.normal_uv_offset = m.normal_transform.offset;
    g.metallic_roughness_texture = m.metallic_roughness_texture;
    g.emissive_texture = m.emissive_texture;
    g.transmission_texture = m.transmission_texture;
    return g;
}

GpuLight to_gpu(const Light& l) {
    GpuLight g{};
    g.color = l.color;
    g.type = std::int32_t(l.type);
    g.position = l.position;
    g.intensity = l.intensity;
    g.direction = l.direction;
    g.range = l.range;
    g.inner_cone = l.inner_cone;
    g.outer_cone = l.outer_cone;
    g.cos_inner = std::cos(l.inner_cone);
    g.cos_outer = std::cos(l.outer_cone);
    return g;
}

GpuAreaLight to_gpu(const AreaLight& l) {
    GpuAreaLight g{};
    g.corner = l.corner;
    g.area = l.area;
    g.edge_u = l.edge_u;
    g.first_triangle = l.first_triangle;
    g.edge_v = l.edge_v;
    g.triangle_count = l.triangle_count;
    g.uv_corner = l.uv_corner;
    g.uv_edge_u = l.uv_edge_u;
    g.uv_edge_v = l.uv_edge_v;
    g.material = l.material;
    g.flags = (l.parallelogram ? kAreaLightParallelogram : 0u) | (l.two_sided ? kAreaLightTwoSided : 0u);
    g.cdf_first = l.cdf_first;
    return g;
}

namespace {
template <class T, class U, class F>
std::vector<T> convert(const std::vector<U>& in, F f) {
    std::vector<T> out;
    out.reserve(in.size());
    for (const U& u : in) out.push_back(f(u));
    return out;
}
}  // namespace

std::size_t GpuScene::upload(const Scene& scene) {
    if (scene.still_id != 0 && scene.still_id == resident_id_) {
        upload_camera(scene.camera, scene.background);
        return 0;
    }
    resident_id_ = 0;   // until this upload is whole
    const std::uint64_t bytes_before = gl_counters().upload_bytes;
    const std::size_t vertices = scene.positions.size();
    if (scene.normals.size() != vertices || scene.uvs.size() != vertices || vertices != scene.triangle_count() * 3)
        throw std::invalid_argument("GpuScene::upload: positions/normals/uvs/material_ids sizes disagree");
    ambient_ = scene.ambient;
    positions_.assign(convert<glm::vec4>(scene.positions, [](const glm::vec3& p) { return glm::vec4(p, 1.0f); }));
    // With normal maps (docs/shading.md), the tangents follow the normals in the same buffer: vertex i's tangent is
    // entry 3 * triangles + i (no extra binding, and no bytes at all for scenes without normal maps).
    std::vector<glm::vec4> normals = convert<glm::vec4>(scene.normals, [](const glm::vec3& n) { return glm::vec4(n, 0.0f); });
    if (scene.tangents.size() == vertices) normals.insert(normals.end(), scene.tangents.begin(), scene.tangents.end());
    normals_.assign(normals);
    // Vertex colours (COLOR_0) follow the texture coordinates the same way: vertex i's RGBA is entries 3 * triangles
    // + 2i and + 2i + 1 (scene.glsl, rt_vertex_color), so the cut-out test, which reads the uvs, reads them too.
    vertex_colors_ = scene.colors.size() == vertices && vertices > 0;
    if (!vertex_colors_ && !scene.colors.empty())
        throw std::invalid_argument("GpuScene::upload: colors and positions sizes disagree");
    std::vector<glm::vec2> uvs = scene.uvs;
    if (vertex_colors_)
        for (const glm::vec4& c : scene.colors) uvs.insert(uvs.end(), {glm::vec2(c.x, c.y), glm::vec2(c.z, c.w)});
    uvs_.assign(uvs);
    material_ids_.assign(scene.material_ids);
    materials_.assign(convert<GpuMaterial>(scene.materials, [](const Material& m) { return to_gpu(m); }));
    lights_.assign(convert<GpuLight>(scene.lights, [](const Light& l) { return to_gpu(l); }));
    // Area lights (scene.glsl, RT_AREA_LIGHTS): their records, then the running areas; no buffer without them.
    if (scene.area_lights.empty()) {
        area_lights_ = Buffer();
    } else {
        std::vector<GpuAreaLight> records = convert<GpuAreaLight>(scene.area_lights, [](const AreaLight& l) { return to_gpu(l); });
        std::vector<float> data(records.size() * sizeof(GpuAreaLight) / sizeof(float) + scene.area_light_cdf.size());
        std::memcpy(data.data(), records.data(), records.size() * sizeof(GpuAreaLight));
        std::copy(scene.area_light_cdf.begin(), scene.area_light_cdf.end(),
                  data.begin() + std::ptrdiff_t(records.size() * sizeof(GpuAreaLight) / sizeof(float)));
        area_lights_.assign(data);
    }

    upload_textures(scene);
    environment_.upload(scene.environment);

    const std::size_t scene_bytes = std::size_t(gl_counters().upload_bytes - bytes_before);
    block_.camera = to_gpu(scene.camera);
    block_.background = scene.background;
    block_.triangle_count = std::uint32_t(scene.triangle_count());
    block_.material_count = std::uint32_t(scene.materials.size());
    block_.light_count = std::uint32_t(scene.lights.size());
    block_.area_light_count = std::uint32_t(scene.area_lights.size());
    block_.texture_count = std::uint32_t(scene.textures.size());
    block_.environment_rotation = scene.environment ? scene.environment->rotation : glm::vec2(0.0f);
    if (!ubo_) ubo_ = Buffer(sizeof(GpuSceneBlock));
    ubo_.upload(&block_, sizeof block_);
    check_gl("GpuScene::upload");
    resident_id_ = scene.still_id;
    return scene_bytes;
}

void GpuScene::upload_camera(const Camera& camera, const glm::vec3& background) {
    block_.camera = to_gpu(camera);
    block_.background = background;
    if (!ubo_) ubo_ = Buffer(sizeof(GpuSceneBlock));
    ubo_.upload(&block_, sizeof block_);
}

void GpuScene::upload_textures(const Scene& scene) {
    // One buffer: the sRGB and alpha tables of rt::sample_texture, a GpuTextureInfo per texture, then each texture's
    // RGBA8 bytes (the file's, decoded in the shader exactly as the CPU does) right after the previous one. Memory is
    // the sum of the texture sizes: no texture is padded to the largest.
    std::vector<float> lut(512);
    for (int i = 0; i < 256; ++i) {
        lut[std::size_t(i)] = srgb_to_linear(float(i) / 255.0f);
        lut[256 + std::size_t(i)] = float(i) / 255.0f;
    }
    const std::size_t lut_bytes = lut.size() * sizeof(float);
    std::vector<GpuTextureInfo> info;
    std::size_t word = scene.textures.size() * sizeof(GpuTextureInfo) / 4;   // the texels start after the table
    for (const Texture& t : scene.textures) {
        const std::size_t texels = t.width > 0 && t.height > 0 ? std::size_t(t.width) * std::size_t(t.height) : 0;
        if (t.rgba8.size() < texels * 4)
            throw std::invalid_argument("GpuScene: texture '" + t.name + "' has fewer bytes than width*height*4");
        const int sampler = (t.nearest ? 1 : 0) | int(t.wrap_s) << 1 | int(t.wrap_t) << 3;
        info.push_back({t.width, t.height, sampler, std::uint32_t(word)});
        word += texels;
    }
    const std::size_t bytes = lut_bytes + word * 4;
    if (bytes > max_storage_block_bytes() || word > 0xffffffffu)
        throw SceneError("the scene's textures (" + std::to_string(scene.textures.size()) + ") need " +
                         describe_bytes(bytes) + " in one GPU shader storage block, beyond this GPU's limit "
                         "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE) of " + describe_bytes(max_storage_block_bytes()));
    textures_.resize(bytes);
    textures_.upload(lut.data(), lut_bytes);
    if (!info.empty()) textures_.upload(info.data(), info.size() * sizeof(GpuTextureInfo), lut_bytes);
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        if (t.width > 0 && t.height > 0)
            textures_.upload(t.rgba8.data(), std::size_t(t.width) * std::size_t(t.height) * 4,
                             lut_bytes + std::size_t(info[i].first) * 4);
    }
    check_gl("GpuScene textures");
}

void GpuScene::bind() const {
    positions_.bind(kBindingPositions);
    normals_.bind(kBindingNormals);
    uvs_.bind(kBindingUvs);
    material_ids_.bind(kBindingMaterialIds);
    materials_.bind(kBindingMaterials);
    lights_.bind(kBindingLights);
    textures_.bind(kBindingTextureInfo);
    if (area_lights_) area_lights_.bind(kBindingAreaLights);
    ubo_.bind(kUboScene, GL_UNIFORM_BUFFER);
    environment_.bind();   // nothing without an environment
}

std::size_t GpuScene::bytes() const {
    return positions_.size() + normals_.size() + uvs_.size() + material_ids_.size() + materials_.size() +
           lights_.size() + area_lights_.size() + textures_.size() + ubo_.size();
}

}  // namespace rt::gpu
