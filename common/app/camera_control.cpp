#include "camera_control.h"

#include <algorithm>
#include <cmath>

namespace rt {

namespace {

constexpr glm::vec3 kWorldUp{0.0f, 1.0f, 0.0f};

// An orthonormal frame looking along `forward` with the horizon level (right has no Y component).
void look_along(Camera& camera, glm::vec3 forward) {
    camera.forward = glm::normalize(forward);
    glm::vec3 right = glm::cross(camera.forward, kWorldUp);
    if (glm::length(right) < 1e-6f) right = camera.right;   // straight up or down: keep the old right axis
    camera.right = glm::normalize(right);
    camera.up = glm::cross(camera.right, camera.forward);
}

// The height of the view at distance d from the camera (a perspective camera's view grows with d).
float view_height(const Camera& camera, float d) {
    if (camera.projection == Projection::Orthographic) return 2.0f * camera.ymag;
    return 2.0f * d * std::tan(camera.yfov * 0.5f);
}

}  // namespace

CameraRig make_rig(const Camera& camera, const Bounds& bounds) {
    const float size = bounds.empty() ? 1.0f : std::max(bounds.diagonal(), 1e-3f);
    const float depth = bounds.empty() ? size : glm::dot(bounds.center() - camera.position, camera.forward);
    return {camera, camera.position + camera.forward * std::max(depth, 0.1f * size)};
}

CameraRig orbit(const CameraRig& rig, glm::vec2 drag, float radians_per_pixel) {
    // The camera's place on a sphere about the pivot, as azimuth (around +Y) and elevation; dragging right turns the
    // scene to the right (the camera goes left), dragging down tips it toward the viewer (the camera goes up).
    const glm::vec3 offset = rig.camera.position - rig.pivot;
    const float r = glm::length(offset);
    if (r <= 0.0f) return rig;
    const float max_pitch = glm::radians(kMaxPitchDegrees);
    const float azimuth = std::atan2(offset.x, offset.z) - drag.x * radians_per_pixel;
    const float elevation =
        std::clamp(std::asin(std::clamp(offset.y / r, -1.0f, 1.0f)) + drag.y * radians_per_pixel, -max_pitch, max_pitch);
    const glm::vec3 dir{std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
    CameraRig out = rig;
    out.camera.position = rig.pivot + r * dir;
    look_along(out.camera, -dir);
    return out;
}

CameraRig pan(const CameraRig& rig, glm::vec2 drag, int viewport_height) {
    const float d = glm::dot(rig.pivot - rig.camera.position, rig.camera.forward);
    const float units_per_pixel = view_height(rig.camera, d) / float(std::max(viewport_height, 1));
    // Screen y grows downward: dragging down moves the scene down, so the camera goes up.
    const glm::vec3 shift = (-drag.x * rig.camera.right + drag.y * rig.camera.up) * units_per_pixel;
    CameraRig out = rig;
    out.camera.position += shift;
    out.pivot += shift;
    return out;
}

CameraRig zoom(const CameraRig& rig, float steps) {
    const float factor = std::pow(kZoomPerStep, steps);
    CameraRig out = rig;
    if (rig.camera.projection == Projection::Orthographic) {   // moving closer changes nothing: shrink the view
        out.camera.xmag *= factor;
        out.camera.ymag *= factor;
        return out;
    }
    out.camera.position = rig.pivot + (rig.camera.position - rig.pivot) * factor;   // factor > 0: never past it
    return out;
}

CameraRig move(const CameraRig& rig, glm::vec3 direction, float distance) {
    const glm::vec3 shift =
        (direction.x * rig.camera.right + direction.y * rig.camera.up + direction.z * rig.camera.forward) * distance;
    CameraRig out = rig;
    out.camera.position += shift;
    out.pivot += shift;
    return out;
}

}  // namespace rt
