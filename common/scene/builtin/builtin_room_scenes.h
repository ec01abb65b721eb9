// Built-in scenes shaped like the test scenes of Roger et al. (2007) and Garanzha & Loop (2010), for stage 05's
// table: builtin:mirror_box and builtin:office; and the rooms lit by area lights, builtin:office_soft and
// builtin:soft_shadows (builtin_scenes.h lists them).
#pragma once

#include "common/scene/scene.h"

namespace rt {

// builtin:mirror_box: a 440-triangle object inside a closed box of six mirrors (reflection-heavy).
SceneAsset mirror_box_scene();

// builtin:office: a furnished room, 25,424 triangles in 330 meshes, one light (shadow-heavy).
SceneAsset office_scene();

// builtin:office_soft: the office lit by a ceiling panel (an area light) instead of its point light: soft shadows,
// many coherent shadow rays per hit.
SceneAsset office_soft_scene();

// builtin:soft_shadows: a room lit only by a rectangular ceiling light, with a pillar, a ball and a low table whose
// shadows have penumbrae that widen with the distance from what casts them.
SceneAsset soft_shadows_scene();

}  // namespace rt
