// The glTF loader's materials and textures (gltf_loader.h): metallic-roughness and the KHR_materials_* extensions
// the renderer reads, alpha modes, texture references and their KHR_texture_transform, and decoding images to RGBA8.
#include <cmath>
#include <cstring>
#include <limits>

#include <tiny_gltf.h>

#include "gltf_common.h"
#include "gltf_loader.h"

namespace rt::gltf_detail {

// A material's texture reference: its index, or -1 when it has none or uses a texture coordinate set other than
// TEXCOORD_0 (the only one flattened; warned about).
int Loader::texture_index(int index, int tex_coord, const std::string& what) {
    if (index < 0) return -1;
    check_index(index, model.textures.size(), what);
    if (tex_coord != 0) {
        warn(what + " uses TEXCOORD_" + std::to_string(tex_coord) + "; only TEXCOORD_0 is supported, texture ignored");
        return -1;
    }
    return index;
}


// A texture reference inside an extension object ({"index": i, "texCoord": n}), as texture_index.
int Loader::extension_texture(const tinygltf::Value* object, const std::string& key, const std::string& material) {
    const tinygltf::Value* info = object ? member(*object, key) : nullptr;
    if (!info || !info->IsObject()) return -1;
    const std::string what = material + ": " + key;
    const auto integer = [&](const char* field, double fallback) {
        const double v = number(info, field, fallback);
        if (v != std::floor(v) || v < -1.0 || v > 2147483647.0)
            invalid(what + " " + field + " is " + describe(v) + ", not a valid index");
        return int(v);
    };
    return texture_index(integer("index", -1.0), integer("texCoord", 0.0), what);
}


Material Loader::material(const tinygltf::Material& m, std::size_t index) {
    Material out;
    out.name = m.name;
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    const std::string name = "material " + std::to_string(index);
    out.base_color = values<4>(pbr.baseColorFactor, name + ": baseColorFactor", glm::vec4(1.0f), 0.0f, 1.0f);
    out.metallic = value(pbr.metallicFactor, name + ": metallicFactor", 0.0f, 1.0f);
    out.roughness = value(pbr.roughnessFactor, name + ": roughnessFactor", 0.0f, 1.0f);
    if (pbr.baseColorTexture.index >= 0) {
        check_index(pbr.baseColorTexture.index, model.textures.size(), name + ": texture");
        if (texture_transform(pbr.baseColorTexture.extensions, pbr.baseColorTexture.texCoord,
                              name + ": baseColorTexture", out.base_color_transform))
            out.base_color_texture = pbr.baseColorTexture.index;
    }
    if (m.normalTexture.index >= 0) {
        check_index(m.normalTexture.index, model.textures.size(), name + ": normalTexture");
        if (texture_transform(m.normalTexture.extensions, m.normalTexture.texCoord, name + ": normalTexture",
                              out.normal_transform))
            out.normal_texture = m.normalTexture.index;
        out.normal_scale = value(m.normalTexture.scale, name + ": normalTexture scale");
    }
    // KHR_materials_volume: attenuationColor [0, 1], attenuationDistance > 0 (absent: infinite, no absorption),
    // thicknessFactor >= 0 (0: thin-walled). JSON cannot spell infinity, so a given distance is finite.
    if (const tinygltf::Value* volume = extension(m.extensions, "KHR_materials_volume")) {
        out.thickness = value(number(volume, "thicknessFactor", 0.0), name + ": thicknessFactor", 0.0f);
        out.attenuation_color = values<3>(numbers(volume, "attenuationColor", {}), name + ": attenuationColor",
                                          glm::vec3(1.0f), 0.0f, 1.0f);
        if (const tinygltf::Value* d = member(*volume, "attenuationDistance"); d && d->IsNumber())
            out.attenuation_distance = value(d->GetNumberAsDouble(), name + ": attenuationDistance",
                                             std::numeric_limits<float>::min());
    }
    out.metallic_roughness_texture = texture_index(pbr.metallicRoughnessTexture.index,
                                                   pbr.metallicRoughnessTexture.texCoord,
                                                   name + ": metallicRoughnessTexture");
    out.emissive_texture = texture_index(m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                         name + ": emissiveTexture");
    if (pbr.metallicRoughnessTexture.extensions.count("KHR_texture_transform") ||
        m.emissiveTexture.extensions.count("KHR_texture_transform"))
        warn(name + ": KHR_texture_transform is read on baseColorTexture and normalTexture only; ignored on the "
                    "metallic-roughness and emissive textures");
    const float strength = value(number(extension(m.extensions, "KHR_materials_emissive_strength"),
                                        "emissiveStrength", 1.0),
                                 name + ": emissiveStrength", 0.0f);
    // factor <= 1, so the product fits a float too
    out.emissive = values<3>(m.emissiveFactor, name + ": emissiveFactor", glm::vec3(0.0f), 0.0f, 1.0f) * strength;
    const tinygltf::Value* transmission = extension(m.extensions, "KHR_materials_transmission");
    out.transmission = value(number(transmission, "transmissionFactor", 0.0), name + ": transmissionFactor", 0.0f, 1.0f);
    out.transmission_texture = extension_texture(transmission, "transmissionTexture", name);
    out.ior = value(number(extension(m.extensions, "KHR_materials_ior"), "ior", 1.5), name + ": ior", 1.0f);
    const tinygltf::Value* specular = extension(m.extensions, "KHR_materials_specular");
    out.specular = value(number(specular, "specularFactor", 1.0), name + ": specularFactor", 0.0f, 1.0f);
    out.specular_color = values<3>(numbers(specular, "specularColorFactor", {}), name + ": specularColorFactor",
                                   glm::vec3(1.0f), 0.0f);
    if (m.alphaMode == "MASK") out.alpha_mode = AlphaMode::Mask;
    else if (m.alphaMode == "BLEND") out.alpha_mode = AlphaMode::Blend;
    else if (m.alphaMode != "OPAQUE") warn(name + ": alphaMode '" + m.alphaMode + "' is unknown; OPAQUE used");
    out.alpha_cutoff = value(m.alphaCutoff, name + ": alphaCutoff", 0.0f);
    out.double_sided = m.doubleSided;
    return out;
}


// A texture reference's KHR_texture_transform (offset, rotation, scale: any float) into `out`. Its texCoord
// overrides the reference's; only TEXCOORD_0 is read, so another set is warned about and the texture ignored
// (returns false).
bool Loader::texture_transform(const tinygltf::ExtensionMap& extensions, int tex_coord, const std::string& what,
                       TextureTransform& out) {
    const tinygltf::Value* t = extension(extensions, "KHR_texture_transform");
    if (t) {
        out.offset = values<2>(numbers(t, "offset", {}), what + " offset", glm::vec2(0.0f));
        out.rotation = value(number(t, "rotation", 0.0), what + " rotation");
        out.scale = values<2>(numbers(t, "scale", {}), what + " scale", glm::vec2(1.0f));
        if (const tinygltf::Value* c = member(*t, "texCoord"); c && c->IsNumber()) tex_coord = c->GetNumberAsInt();
    }
    if (tex_coord == 0) return true;
    warn(what + " uses TEXCOORD_" + std::to_string(tex_coord) + "; only TEXCOORD_0 is supported, texture ignored");
    return false;
}


Texture Loader::texture(const tinygltf::Texture& t, std::size_t index) {
    Texture out;
    out.name = t.name;
    const std::string name = "texture " + std::to_string(index);
    check_index(t.sampler, model.samplers.size(), name + ": sampler");
    if (t.sampler >= 0) {
        const tinygltf::Sampler& s = model.samplers[std::size_t(t.sampler)];
        out.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        auto wrap = [&](int mode, const char* axis) {
            if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::ClampToEdge;
            if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::MirroredRepeat;
            if (mode != TINYGLTF_TEXTURE_WRAP_REPEAT)
                warn(name + ": sampler " + std::to_string(t.sampler) + " " + axis + " " + std::to_string(mode) +
                     " is not a glTF wrap mode; REPEAT");
            return Wrap::Repeat;
        };
        out.wrap_s = wrap(s.wrapS, "wrapS");
        out.wrap_t = wrap(s.wrapT, "wrapT");
    }
    check_index(t.source, model.images.size(), name + ": image");
    if (t.source < 0) {
        warn(name + ": no image source; using white");
        out.width = out.height = 1;
        out.rgba8 = {255, 255, 255, 255};
        return out;
    }
    const tinygltf::Image& img = model.images[std::size_t(t.source)];
    if (out.name.empty()) out.name = img.name;
    const int comps = img.component;
    const int bytes = img.bits == 16 ? 2 : img.bits == 8 ? 1 : 0;
    if (img.width <= 0 || img.height <= 0 || comps < 1 || comps > 4 || bytes == 0)   // gltf_files.cpp left it
        invalid(name + ": image " + std::to_string(t.source) + " is not a PNG or JPEG image");
    const std::size_t pixels = std::size_t(img.width) * std::size_t(img.height);
    if (img.image.size() < pixels * std::size_t(comps) * std::size_t(bytes))
        invalid(name + ": image " + std::to_string(t.source) + " has too little pixel data");
    out.width = img.width;
    out.height = img.height;
    out.rgba8.resize(pixels * 4);
    // Expand grey, grey+alpha and RGB to RGBA; 16-bit channels keep their high byte.
    auto channel = [&](std::size_t pixel, int c) -> std::uint8_t {
        const std::size_t at = (pixel * std::size_t(comps) + std::size_t(c)) * std::size_t(bytes);
        if (bytes == 1) return img.image[at];
        std::uint16_t v;
        std::memcpy(&v, &img.image[at], 2);
        return std::uint8_t(v >> 8);
    };
    for (std::size_t i = 0; i < pixels; ++i) {
        std::uint8_t* px = &out.rgba8[4 * i];
        if (comps <= 2) {
            px[0] = px[1] = px[2] = channel(i, 0);
            px[3] = comps == 2 ? channel(i, 1) : 255;
        } else {
            for (int c = 0; c < 3; ++c) px[c] = channel(i, c);
            px[3] = comps == 4 ? channel(i, 3) : 255;
        }
    }
    return out;
}

}  // namespace rt::gltf_detail
