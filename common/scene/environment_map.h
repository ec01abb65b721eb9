// The environment: an equirectangular radiance map that rays leaving the scene see instead of the background
// colour (--environment FILE, docs/shading.md "The environment"). It is background, not lighting: Whitted's lights
// are the scene's lights only. Loaded by the app layer (common/app/environment_file.h) before any rendering and held
// by every flattened Scene of the run (Scene::environment), so a GPU stage uploads it once.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rt {

struct Environment {
    std::string file;                 // where it was read from (messages, stats)
    int width = 0, height = 0;        // texels; u runs along the width, v down the height
    // Linear RGB radiance times --environment-intensity, alpha 1; row 0 = the top of the image = straight up (+Y).
    // Every value is finite and in [0, kMaxRadiance] (the loader refuses anything else).
    std::vector<glm::vec4> texels;
    float rotation_degrees = 0.0f;    // --environment-rotation: the map turned about +Y (right-handed)
    float intensity = 1.0f;           // --environment-intensity, already applied to the texels
    // (cos, sin) of the rotation in radians, computed once in float: what the C++ and GLSL lookups both use.
    glm::vec2 rotation{1.0f, 0.0f};
};

}  // namespace rt
