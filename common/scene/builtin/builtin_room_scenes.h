// Built-in scenes shaped like the test scenes of Roger et al. (2007) and Garanzha & Loop (2010), for stage 05's
// table: builtin:mirror_box and builtin:office (builtin_scenes.h lists them).
#pragma once

#include "common/scene/scene.h"

namespace rt {

// builtin:mirror_box: a 440-triangle object inside a closed box of six mirrors (reflection-heavy).
SceneAsset mirror_box_scene();

// builtin:office: a furnished room, 25,424 triangles in 330 meshes, one light (shadow-heavy).
SceneAsset office_scene();

}  // namespace rt
