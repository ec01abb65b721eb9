// Tangents for normal maps (docs/shading.md, "Normal maps"), in a primitive's own space: glTF's TANGENT attribute
// when the file has one, else generated here from the texture coordinates.
#pragma once

#include <vector>

#include "scene.h"

namespace rt {

// One tangent per vertex of `prim` (xyz unit, w = +1 or -1): per triangle, the direction in which u grows,
// dP/du, and the direction in which v shrinks, -dP/dv (the normal texture's +Y: glTF images have v down), from the
// edges and uv differences (Lengyel 2001); summed over the triangles around each vertex of the index buffer,
// weighted by the triangle's uv-space area; then made orthogonal to the vertex normal (Gram-Schmidt), with w = -1
// where -dP/dv lies against cross(n, t) (mirrored uvs). Vertices without usable uvs (none, or all of their
// triangles degenerate in uv) get any unit tangent orthogonal to the normal, w = 1. Not MikkTSpace: see the docs.
std::vector<glm::vec4> generate_tangents(const Primitive& prim);

// prim.tangents when it has one per vertex, else generate_tangents(prim).
std::vector<glm::vec4> primitive_tangents(const Primitive& prim);

}  // namespace rt
