// What a scene lacks, supplied (docs/shading.md, "Defaults"): the auto-framed camera, the key light placed for it,
// and the headlight for a camera of the file's own. Declared in scene.h; the flattening that calls them is scene.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "scene.h"

namespace rt {

// The auto-framed camera (docs/shading.md, "Defaults"): a perspective camera with a 45 degree vertical field of view,
// looking at the centre of the bounds from the direction normalize(0, 0.25, 1) (in front, slightly raised), at the
// distance where the bounding sphere (radius = half the diagonal) fits in both the vertical and the horizontal field of
// view: d = r / sin(min(yfov, xfov) / 2). znear = r / 1000; zfar infinite. camera.aspect is left 0 (the image's);
// `aspect` is only used for framing. Empty bounds frame a unit sphere at the origin.
Camera default_camera(const Bounds& bounds, float aspect) {
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) aspect = 1.0f;
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    float radius = 0.5f * bounds.diagonal();
    if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;

    Camera cam;
    cam.name = "default camera";
    cam.projection = Projection::Perspective;
    cam.yfov = glm::radians(45.0f);
    cam.aspect = 0.0f;
    const float half_y = 0.5f * cam.yfov;
    const float half_x = std::atan(std::tan(half_y) * aspect);
    const float distance = radius / std::sin(std::min(half_y, half_x));
    const glm::vec3 to_eye = glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));
    cam.znear = 1e-3f * radius;
    cam.zfar = 0.0f;
    cam.position = center + distance * to_eye;
    cam.forward = -to_eye;
    const glm::vec3 world_up(0.0f, 1.0f, 0.0f);
    cam.up = glm::normalize(world_up - glm::dot(world_up, cam.forward) * cam.forward);
    cam.right = glm::normalize(glm::cross(cam.forward, cam.up));
    return cam;
}

// The key light (docs/shading.md, "Defaults"): a white point light at center + diagonal * (0.5, 1.0, 0.8) (above, in
// front and to the right of the bounds), with intensity pi * distance^2 so that the irradiance at the centre is pi and
// a white Lambertian surface facing the light shades to 1 (kd / pi * I / d^2 * cos). Empty bounds use a unit diagonal
// at the origin.
Light default_light(const Bounds& bounds) {
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    float diagonal = bounds.diagonal();
    if (!(diagonal > 0.0f) || !std::isfinite(diagonal)) diagonal = 1.0f;
    Light light;
    light.name = "default light";
    light.type = LightType::Point;
    light.color = glm::vec3(1.0f);
    light.position = center + diagonal * glm::vec3(0.5f, 1.0f, 0.8f);
    const float distance = glm::length(light.position - center);
    light.intensity = 3.14159265358979f * distance * distance;
    light.direction = glm::normalize(center - light.position);
    return light;
}

bool strictly_inside(const Bounds& bounds, const glm::vec3& p) {
    return !bounds.empty() && glm::all(glm::greaterThan(p, bounds.lo)) && glm::all(glm::lessThan(p, bounds.hi));
}

// The headlight (docs/shading.md, "Defaults"): a white point light at the camera, as a viewer's headlight, so
// everything the camera sees directly is lit (its shadow rays run back along the camera rays) whatever walls stand
// around it. Its intensity is pi * d^2, so a white Lambertian surface facing the camera at distance d shades to 1,
// as under the key light; nearer surfaces are brighter (1/d^2). d: for a camera strictly inside the bounds, the
// distance to where its view axis leaves them (the slab method: the smallest of the three exit distances); for one
// outside, the distance to the bounds' centre. Empty or flat bounds (d not positive and finite) use half the
// diagonal, or 1.
Light default_headlight(const Bounds& bounds, const Camera& camera) {
    float exit = std::numeric_limits<float>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        const float f = camera.forward[axis];
        if (f > 0.0f) exit = std::min(exit, (bounds.hi[axis] - camera.position[axis]) / f);
        if (f < 0.0f) exit = std::min(exit, (bounds.lo[axis] - camera.position[axis]) / f);
    }
    float distance = strictly_inside(bounds, camera.position) ? exit
                     : bounds.empty()                         ? 0.0f
                                                              : glm::length(bounds.center() - camera.position);
    if (!(distance > 0.0f) || !std::isfinite(distance)) distance = 0.5f * bounds.diagonal();
    if (!(distance > 0.0f) || !std::isfinite(distance)) distance = 1.0f;
    Light light;
    light.name = "default headlight";
    light.type = LightType::Point;
    light.color = glm::vec3(1.0f);
    light.position = camera.position;
    light.intensity = std::min(3.14159265358979f * distance * distance, kMaxRadiance);
    light.direction = camera.forward;
    return light;
}

}  // namespace rt
