#include "gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "../trace/shading.h"
#include "bindings.h"

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

GpuScene::GpuScene(GpuScene&& o) noexcept
    : positions_(std::move(o.positions_)), normals_(std::move(o.normals_)), uvs_(std::move(o.uvs_)),
      material_ids_(std::move(o.material_ids_)), materials_(std::move(o.materials_)), lights_(std::move(o.lights_)),
      texture_info_(std::move(o.texture_info_)), ubo_(std::move(o.ubo_)),
      texture_array_(std::exchange(o.texture_array_, 0)), tex_width_(o.tex_width_), tex_height_(o.tex_height_),
      tex_layers_(o.tex_layers_), texture_bytes_(o.texture_bytes_), block_(o.block_) {}

GpuScene& GpuScene::operator=(GpuScene&& o) noexcept {
    if (this != &o) {
        this->~GpuScene();
        new (this) GpuScene(std::move(o));
    }
    return *this;
}

GpuScene::~GpuScene() {
    if (texture_array_ && glDeleteTextures) glDeleteTextures(1, &texture_array_);
    texture_array_ = 0;
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

void GpuScene::upload(const Scene& scene) {
    const std::size_t vertices = scene.positions.size();
    if (scene.normals.size() != vertices || scene.uvs.size() != vertices || vertices != scene.triangle_count() * 3)
        throw std::invalid_argument("GpuScene::upload: positions/normals/uvs/material_ids sizes disagree");
    positions_.assign(convert<glm::vec4>(scene.positions, [](const glm::vec3& p) { return glm::vec4(p, 1.0f); }));
    normals_.assign(convert<glm::vec4>(scene.normals, [](const glm::vec3& n) { return glm::vec4(n, 0.0f); }));
    uvs_.assign(scene.uvs);
    material_ids_.assign(scene.material_ids);
    materials_.assign(convert<GpuMaterial>(scene.materials, [](const Material& m) { return to_gpu(m); }));
    lights_.assign(convert<GpuLight>(scene.lights, [](const Light& l) { return to_gpu(l); }));

    upload_textures(scene);

    block_.camera = to_gpu(scene.camera);
    block_.background = scene.background;
    block_.triangle_count = std::uint32_t(scene.triangle_count());
    block_.material_count = std::uint32_t(scene.materials.size());
    block_.light_count = std::uint32_t(scene.lights.size());
    block_.texture_count = std::uint32_t(scene.textures.size());
    if (!ubo_) ubo_ = Buffer(sizeof(GpuSceneBlock));
    ubo_.upload(&block_, sizeof block_);
    check_gl("GpuScene::upload");
}

void GpuScene::upload_camera(const Camera& camera, const glm::vec3& background) {
    block_.camera = to_gpu(camera);
    block_.background = background;
    if (!ubo_) ubo_ = Buffer(sizeof(GpuSceneBlock));
    ubo_.upload(&block_, sizeof block_);
}

void GpuScene::upload_textures(const Scene& scene) {
    // Texture array of RGBA8UI (the file's bytes, decoded in the shader exactly as the CPU does), sized to the
    // largest texture; at least 1x1x1 so the sampler is always complete.
    int w = 1, h = 1;
    for (const Texture& t : scene.textures) {
        if (t.width > 0 && t.height > 0 && t.rgba8.size() < std::size_t(t.width) * std::size_t(t.height) * 4)
            throw std::invalid_argument("GpuScene: texture '" + t.name + "' has fewer bytes than width*height*4");
        w = std::max(w, t.width);
        h = std::max(h, t.height);
    }
    const int layers = int(std::max<std::size_t>(1, scene.textures.size()));
    GLint max_size = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (w > max_size || h > max_size || layers > max_layers)
        throw std::runtime_error("GpuScene: textures need a " + std::to_string(w) + "x" + std::to_string(h) + "x" +
                                 std::to_string(layers) + " array, beyond this GPU's limits (" +
                                 std::to_string(max_size) + ", " + std::to_string(max_layers) + " layers)");
    if (!texture_array_ || w != tex_width_ || h != tex_height_ || layers != tex_layers_) {
        // Immutable storage: a new size needs a new texture.
        if (texture_array_) glDeleteTextures(1, &texture_array_);
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_array_);
        glTextureStorage3D(texture_array_, 1, GL_RGBA8UI, w, h, layers);
        // Integer textures must not be filtered; sampling is done by hand with texelFetch anyway.
        glTextureParameteri(texture_array_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture_array_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_array_, GL_TEXTURE_MAX_LEVEL, 0);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    std::vector<GpuTextureInfo> info;
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        info.push_back({t.width, t.height, t.nearest ? 1 : 0, int(i)});
        if (t.width > 0 && t.height > 0)
            glTextureSubImage3D(texture_array_, 0, 0, 0, GLint(i), t.width, t.height, 1, GL_RGBA_INTEGER,
                                GL_UNSIGNED_BYTE, t.rgba8.data());
    }
    tex_width_ = w;
    tex_height_ = h;
    tex_layers_ = layers;
    texture_bytes_ = std::size_t(w) * std::size_t(h) * std::size_t(layers) * 4;
    // The same sRGB and alpha tables as rt::sample_texture, then the per-texture info.
    std::vector<float> lut(512);
    for (int i = 0; i < 256; ++i) {
        lut[std::size_t(i)] = srgb_to_linear(float(i) / 255.0f);
        lut[256 + std::size_t(i)] = float(i) / 255.0f;
    }
    texture_info_.resize(lut.size() * sizeof(float) + std::max<std::size_t>(1, info.size()) * sizeof(GpuTextureInfo));
    texture_info_.upload(lut.data(), lut.size() * sizeof(float));
    if (!info.empty()) texture_info_.upload(info.data(), info.size() * sizeof(GpuTextureInfo), lut.size() * sizeof(float));
    check_gl("GpuScene textures");
}

void GpuScene::bind() const {
    positions_.bind(kBindingPositions);
    normals_.bind(kBindingNormals);
    uvs_.bind(kBindingUvs);
    material_ids_.bind(kBindingMaterialIds);
    materials_.bind(kBindingMaterials);
    lights_.bind(kBindingLights);
    texture_info_.bind(kBindingTextureInfo);
    ubo_.bind(kUboScene, GL_UNIFORM_BUFFER);
    glBindTextureUnit(kTextureUnitTextures, texture_array_);
}

std::size_t GpuScene::bytes() const {
    return positions_.size() + normals_.size() + uvs_.size() + material_ids_.size() + materials_.size() +
           lights_.size() + texture_info_.size() + ubo_.size() + texture_bytes_;
}

}  // namespace rt::gpu
