// Built-in scenes for the surface effects (docs/shading.md, "Absorption", "Normal maps", "Texture
// transform"): each one uses its effect where a golden image shows it.
#pragma once

#include "common/scene/scene.h"

namespace rt {

// builtin:absorption: four glass slabs of one KHR_materials_volume material in front of a checkered wall, from a
// thin-walled one (thickness 0: no absorption) to 0.9 m deep; the colour deepens with the depth.
SceneAsset absorption_scene();

// builtin:normal_map: a wall (given TANGENT attribute) and a floor (generated tangents, KHR_texture_transform) with a
// procedural bump normal texture, a normal-mapped sphere (generated tangents on a curved mesh) and a mirror sphere
// that shows the bumps.
SceneAsset normal_map_scene();

// builtin:material_maps: textures that scale material factors texel by texel (a metallic-roughness floor of mirror
// metal and rough plastic, an emissive panel).
SceneAsset material_maps_scene();

// builtin:cutouts: alpha cut-outs (a MASK fence with holes casting a shadow, a mirror reflecting it, a BLEND pane).
SceneAsset cutouts_scene();

}  // namespace rt
