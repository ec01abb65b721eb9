// Which Whitted effects a scene needs, and the --effects option.
#include "effects.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace rt {

namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();
}  // namespace

std::vector<std::string> Effects::names() const {
    std::vector<std::string> out;
    if (shadows) out.push_back("shadows");
    if (reflections) out.push_back("reflections");
    if (refractions) out.push_back("refractions");
    if (textures) out.push_back("textures");
    if (absorption) out.push_back("absorption");
    if (normal_maps) out.push_back("normal_maps");
    if (cutouts) out.push_back("cutouts");
    if (blend) out.push_back("blend");
    return out;
}

namespace {

// The range of roughness and metallic a material takes over its metallic-roughness texture (green and blue bytes,
// linear), or its factors when it has none.
struct MetallicRoughnessRange {
    float min_roughness, min_metallic, max_metallic;
};

MetallicRoughnessRange metallic_roughness_range(const Material& m, const std::vector<Texture>* textures) {
    MetallicRoughnessRange r{m.roughness, m.metallic, m.metallic};
    if (!textures || m.metallic_roughness_texture < 0 || std::size_t(m.metallic_roughness_texture) >= textures->size())
        return r;
    const Texture& t = (*textures)[std::size_t(m.metallic_roughness_texture)];
    if (t.rgba8.empty()) return r;
    std::uint8_t g_lo = 255, b_lo = 255, b_hi = 0;
    for (std::size_t i = 0; i + 3 < t.rgba8.size(); i += 4) {
        g_lo = std::min(g_lo, t.rgba8[i + 1]);
        b_lo = std::min(b_lo, t.rgba8[i + 2]);
        b_hi = std::max(b_hi, t.rgba8[i + 2]);
    }
    // Bilinear filtering stays between the extreme texels, so these bound every sample.
    r.min_roughness = m.roughness * (float(g_lo) / 255.0f);
    r.min_metallic = m.metallic * (float(b_lo) / 255.0f);
    r.max_metallic = m.metallic * (float(b_hi) / 255.0f);
    return r;
}

}  // namespace

// docs/shading.md: a surface mirrors when it is not fully rough and has a specular lobe: metallic, or a dielectric
// whose specular weight and colour are non-zero and whose index of refraction differs from 1 (F0 > 0).
bool material_reflects(const Material& m, const std::vector<Texture>* textures) {
    const MetallicRoughnessRange r = metallic_roughness_range(m, textures);
    const float max_specular_color = std::max({m.specular_color.r, m.specular_color.g, m.specular_color.b});
    const bool dielectric_mirror = m.specular > 0.0f && max_specular_color > 0.0f && m.ior != 1.0f;
    return r.min_roughness < 1.0f && (r.max_metallic > 0.0f || dielectric_mirror);
}

// Only the dielectric part of a material can transmit.
bool material_transmits(const Material& m, const std::vector<Texture>* textures) {
    return m.transmission > 0.0f && metallic_roughness_range(m, textures).min_metallic < 1.0f;
}

bool material_absorbs(const Material& m, const std::vector<Texture>* textures) {
    return material_transmits(m, textures) && m.thickness > 0.0f && m.attenuation_distance < kInfinity &&
           m.attenuation_color != glm::vec3(1.0f);
}

bool material_has_normal_map(const Material& m, std::size_t texture_count) {
    return m.normal_texture >= 0 && std::size_t(m.normal_texture) < texture_count;
}

// docs/shading.md, "Alpha: cut-outs and blending": only MASK and BLEND materials are ever see-through.
bool material_cuts_out(const Material& m) { return m.alpha_mode != AlphaMode::Opaque; }
bool material_blends(const Material& m) { return m.alpha_mode == AlphaMode::Blend; }

// Only materials used by at least one triangle count. Shadows are called for whenever a light shines on geometry.
// Proving that nothing can occlude is rarely possible: even a lone convex mesh shadows itself where its interpolated
// normals face a light that its flat triangles face away from (near the terminator of a tessellated sphere), so the
// only shadow-free scenes are those without a light or without triangles.
Effects analyze_effects(const Scene& scene) {
    std::vector<bool> used(scene.materials.size(), false);
    for (std::uint32_t id : scene.material_ids)
        if (id < used.size()) used[id] = true;
    Effects e;
    e.shadows = scene.light_count() > 0 && scene.triangle_count() > 0;   // punctual or area lights
    e.textures = !scene.colors.empty();   // vertex colours vary the base colour as a texture does
    for (std::size_t i = 0; i < used.size(); ++i) {
        if (!used[i]) continue;
        const Material& m = scene.materials[i];
        e.reflections = e.reflections || material_reflects(m, &scene.textures);
        e.refractions = e.refractions || material_transmits(m, &scene.textures);
        for (int t : {m.base_color_texture, m.metallic_roughness_texture, m.emissive_texture, m.transmission_texture})
            e.textures = e.textures || (t >= 0 && std::size_t(t) < scene.textures.size());
        e.absorption = e.absorption || material_absorbs(m, &scene.textures);
        e.normal_maps = e.normal_maps || (material_has_normal_map(m, scene.textures.size()) && !scene.tangents.empty());
        e.cutouts = e.cutouts || material_cuts_out(m);
        e.blend = e.blend || material_blends(m);
    }
    return e;
}

namespace {

// Parses a comma list of effect names; returns false on an unknown or empty word.
bool parse_list(const std::string& spec, Effects& out, std::string* bad_word) {
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = spec.find(',', start);
        std::string word = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const auto first = word.find_first_not_of(" \t"), last = word.find_last_not_of(" \t");
        word = first == std::string::npos ? "" : word.substr(first, last - first + 1);
        if (word == "shadows") out.shadows = true;
        else if (word == "reflections") out.reflections = true;
        else if (word == "refractions") out.refractions = true;
        else if (word == "textures") out.textures = true;
        else if (word == "absorption") out.absorption = true;
        else if (word == "normal_maps") out.normal_maps = true;
        else if (word == "cutouts") out.cutouts = true;
        else if (word == "blend") out.blend = out.cutouts = true;
        else {
            if (bad_word) *bad_word = word;
            return false;
        }
        if (comma == std::string::npos) return true;
        start = comma + 1;
    }
}

}  // namespace

bool is_valid_effects_spec(const std::string& spec) {
    if (spec == "auto" || spec == "all" || spec == "none") return true;
    Effects ignored;
    return parse_list(spec, ignored, nullptr);
}

Effects resolve_effects(const std::string& spec, const Scene& scene) {
    if (spec == "auto") return analyze_effects(scene);
    if (spec == "all") return Effects{true, true, true, true, true, true, true, true};
    if (spec == "none") return Effects{};
    Effects e;
    std::string bad;
    if (!parse_list(spec, e, &bad))
        throw std::invalid_argument("unknown effect '" + bad +
                                    "' in --effects (use auto, all, none or a comma list of shadows, reflections, "
                                    "refractions, textures, absorption, normal_maps, cutouts, blend)");
    return e;
}

}  // namespace rt
