// One traced ray and what it found: the unit of the exact cross-stage checks (--dump-hits FILE).
//
// Every stage can record the rays it traced and their hits; a comparison tool then matches two stages' records ray
// by ray. A ray is identified by (sample, pixel, path, kind, light), never by its position in a queue, so stages
// may trace rays in any order:
//   path  1 for the primary ray of a pixel; the reflection child of a ray with path p has path 2p, its refraction
//         child 2p + 1 (so path < 2^31 limits --max-depth to 30 when hits are recorded);
//   light for a shadow ray, the index of its light (punctual lights first, then area lights: Scene::light_count)
//         and, towards an area light, the cell of the light's sample grid it aims at; a shadow ray has the path of
//         the ray whose hit spawned it.
// File format (little-endian): the 8 bytes "RTHITS\0\1", then HitRecord structs (48 bytes each), in any order.
#pragma once

#include <cstdint>

#include "ray.h"   // RayKind, the kind in kind_light's low byte

namespace rt {


struct HitRecord {
    std::uint32_t sample = 0;      // sample index within the pixel (--spp), 0-based
    std::uint32_t pixel = 0;       // y * width + x
    std::uint32_t path = 1;        // see above
    std::uint32_t kind_light = 0;  // RayKind in bits 0-7; shadow rays: light index in bits 8-23, light sample 24-31
    std::int32_t triangle = -1;    // closest hit's triangle id, -1 for a miss; shadow rays: 1 occluded, -1 not
    float t = 0.0f;                // closest hit's distance along the ray (0 for misses and shadow rays)
    float origin[3] = {0, 0, 0};   // the ray as traced, to tell "same ray, different hit" from "different ray"
    float direction[3] = {0, 0, 0};
};
static_assert(sizeof(HitRecord) == 48);

// kind_light's three fields: the ray's kind, a shadow ray's light, and the cell of an area light's sample grid it
// aims at (0 for punctual lights). A scene has at most kMaxLights lights (scene.h) and a grid at most
// kMaxLightGrid^2 cells (area_light.h), so both fit.
constexpr std::uint32_t pack_kind_light(RayKind kind, std::uint32_t light, std::uint32_t light_sample = 0) {
    return std::uint32_t(kind) | (light & 0xffffu) << 8 | light_sample << 24;
}
constexpr RayKind ray_kind(std::uint32_t kind_light) { return RayKind(kind_light & 0xffu); }
constexpr std::uint32_t light_index(std::uint32_t kind_light) { return (kind_light >> 8) & 0xffffu; }
constexpr std::uint32_t light_sample(std::uint32_t kind_light) { return kind_light >> 24; }

// What one ray of the pixel under --pixel X,Y cost (the ray tree printout, driver.cpp): its ray/triangle tests and
// its traversal's own steps where it has them (03: grid cells walked; 04-05: the ray's leaf pairs, its level-0 node
// tests). Named like its HitRecord by (sample, path, kind_light); a stage may report one ray in several parts
// (a traversal in passes), which add up.
struct RayWork {
    std::uint32_t sample = 0;
    std::uint32_t path = 1;
    std::uint32_t kind_light = 0;
    std::uint64_t tests = 0;
    std::uint64_t steps = 0;
};

inline constexpr char kHitFileMagic[8] = {'R', 'T', 'H', 'I', 'T', 'S', '\0', '\1'};

}  // namespace rt
