// The viewer's camera controls (--window on the GPU stages), as pure functions of the input's deltas so they can be
// tested without a window. The camera orbits, pans and zooms about a pivot point in front of it, and WASD moves
// camera and pivot together. World up is +Y (glTF's); orbiting keeps the horizon level (it drops any roll).
//
//   orbit   drag dx, dy pixels: turn about the pivot, around world up and the camera's right axis (pitch within +-89
//           degrees so the view never flips over the pole)
//   pan     drag dx, dy pixels: slide camera and pivot sideways so the pivot's plane follows the mouse exactly
//   zoom    wheel steps: move toward the pivot (each step 15% closer), never through it
//   move    a direction in the camera's frame (x right, y up, z forward) times a distance
#pragma once

#include <glm/glm.hpp>

#include "common/scene/scene.h"

namespace rt {

struct CameraRig {
    Camera camera;
    glm::vec3 pivot{0.0f};
};

constexpr float kOrbitRadiansPerPixel = 0.005f;
constexpr float kZoomPerStep = 0.85f;       // distance to the pivot times this per wheel step in
constexpr float kMaxPitchDegrees = 89.0f;

// The rig of a scene's camera: the pivot is the point straight ahead at the depth of the scene's centre (at least a
// tenth of the scene's size in front of the camera).
CameraRig make_rig(const Camera& camera, const Bounds& bounds);

CameraRig orbit(const CameraRig& rig, glm::vec2 drag_pixels, float radians_per_pixel = kOrbitRadiansPerPixel);
// `viewport_height` in pixels: a drag of that many pixels pans by the view's height at the pivot's depth.
CameraRig pan(const CameraRig& rig, glm::vec2 drag_pixels, int viewport_height);
CameraRig zoom(const CameraRig& rig, float steps);
CameraRig move(const CameraRig& rig, glm::vec3 direction_in_view, float distance);

}  // namespace rt
