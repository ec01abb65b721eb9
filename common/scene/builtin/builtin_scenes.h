// Procedural scenes built into every stage, selected with --scene builtin:NAME.
#pragma once

#include <string>
#include <vector>

#include "common/scene/scene.h"

namespace rt {

// Names accepted by make_builtin_scene ("spheres" takes a count: "spheres:64").
//   whitted  Whitted's 1980 scene: checkerboard floor, glass sphere, mirror sphere, one point light.
//   cornell  Cornell box with a mirror block and a glass sphere, one point light under the ceiling.
//   diffuse  Only diffuse surfaces and one light: shadows and nothing else.
//   dynamic  Objects that move over time (glTF animations), for --frames.
//   spheres:N  N tessellated spheres on a floor, for scaling tests.
//   far      The whitted scene and its camera translated by (1e4, 1e4, 1e4): a fixed epsilon offset fails there.
//   mirror_box  A 440-triangle object inside a closed box of six mirrors: reflection-heavy (stage 05's table).
//   office   A furnished room, 25,424 triangles in 330 meshes, one light: shadow-heavy (stage 05's table).
//   office_soft  The office lit by a ceiling panel (an area light): soft shadows, many shadow rays per hit.
//   material_maps  A floor whose metallic-roughness texture alternates mirror metal and rough plastic, and a panel
//            with an emissive texture: textures that scale material factors.
//   cutouts  Alpha cut-outs: a fence with holes (MASK) casting a shadow, a mirror reflecting it, a BLEND pane.
//   soft_shadows  A room lit by a rectangular ceiling light only: a pillar, a ball and a table cast penumbrae.
std::vector<std::string> builtin_scene_names();

// The registry as one line, for --help and the "unknown built-in scene" error (the same text in both):
// "whitted, cornell, ..., cutouts; spheres takes a count, spheres:N".
std::string builtin_scene_list();

// Throws SceneError for an unknown name or a bad count.
SceneAsset make_builtin_scene(const std::string& name);

// A UV sphere (shared seam and pole vertices, indexed) and a unit cube, used by the built-in scenes and the tests.
Primitive make_uv_sphere(const glm::vec3& center, float radius, int segments, int rings, int material);
Primitive make_box(const glm::vec3& lo, const glm::vec3& hi, int material);

}  // namespace rt
