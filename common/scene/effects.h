// Which Whitted effects a scene calls for. The stages simulate only those: no shadow rays without a light and an
// occluder, no reflection rays without a reflective material, no refraction rays without a transmissive one, no
// texture lookups without a textured material.
#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace rt {

struct Effects {
    bool shadows = false;
    bool reflections = false;
    bool refractions = false;
    bool textures = false;
    bool absorption = false;    // KHR_materials_volume: Beer-Lambert inside transmitting volumes
    bool normal_maps = false;   // normal textures perturb the shading normal
    bool cutouts = false;       // alphaMode MASK or BLEND: the opacity test where a hit is accepted (common/trace/opacity.h)
    bool blend = false;         // alphaMode BLEND as coverage: shading weighted by alpha, a transparency ray for the
                                // rest (docs/shading.md, "Alpha: cut-outs and blending"); implies cutouts. Without
                                // it, BLEND is read as a cut-out at 0.5.
    bool operator==(const Effects&) const = default;
    std::vector<std::string> names() const;   // e.g. {"shadows", "reflections"}
};

// What the scene needs (--effects auto).
Effects analyze_effects(const Scene& scene);

// Parses the --effects value: "auto", "all", "none" or a comma list of shadows,reflections,refractions,textures,
// absorption,normal_maps,cutouts,blend (blend turns cutouts on too).
// For "auto" returns analyze_effects(scene). Throws std::invalid_argument on an unknown word.
Effects resolve_effects(const std::string& spec, const Scene& scene);
bool is_valid_effects_spec(const std::string& spec);

// Material predicates shared by the analysis and the shading code (docs/shading.md). With the scene's textures,
// a metallic-roughness texture counts at its extremes: the material reflects if its smoothest texel does and
// transmits if its least metallic texel does (without them, the factors alone decide).
bool material_reflects(const Material& m, const std::vector<Texture>* textures = nullptr);
bool material_transmits(const Material& m, const std::vector<Texture>* textures = nullptr);
// A transmitting material with a volume (thickness > 0) and a finite attenuation distance (docs/shading.md,
// "Absorption"); and one with a normal texture (valid index into `texture_count` textures).
bool material_absorbs(const Material& m, const std::vector<Texture>* textures = nullptr);
bool material_has_normal_map(const Material& m, std::size_t texture_count);
bool material_cuts_out(const Material& m);   // alphaMode MASK or BLEND
bool material_blends(const Material& m);     // alphaMode BLEND

}  // namespace rt
