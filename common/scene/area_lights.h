// Gathering the area lights of a frame (docs/shading.md, "Area lights"): flatten (scene.cpp) calls this for each
// node primitive whose material is an area light, once its triangles are in the soup. Internal to rt_scene.
#pragma once

#include <cstdint>
#include <string>

#include "scene.h"

namespace rt {

// Appends the area light made of triangles [first, first + count) of `scene` with `material`: its area, whether it
// is a parallelogram (two triangles whose corners and texture coordinates form one), else the running share of the
// area per triangle. A light of no area (degenerate triangles, overflowing coordinates) emits nothing and is not added.
void add_area_light(Scene& scene, std::uint32_t first, std::uint32_t count, std::uint32_t material,
                    std::string name);

}  // namespace rt
