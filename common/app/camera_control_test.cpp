#include "camera_control.h"

#include <cmath>

#include <gtest/gtest.h>

namespace rt {
namespace {

// A camera at (0, 0, 5) looking down -Z at the origin (glTF's default frame), its pivot at the origin.
CameraRig front_rig() {
    Camera camera;
    camera.position = {0.0f, 0.0f, 5.0f};
    Bounds bounds;
    bounds.add({-1.0f, -1.0f, -1.0f});
    bounds.add({1.0f, 1.0f, 1.0f});
    return make_rig(camera, bounds);
}

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

void expect_orthonormal_frame(const Camera& c) {
    EXPECT_NEAR(glm::length(c.forward), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(c.right), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(c.up), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(c.forward, c.right), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(c.forward, c.up), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(c.right, c.up), 0.0f, 1e-5f);
}

TEST(CameraControl, RigPivotIsStraightAheadAtTheSceneCentresDepth) {
    expect_near(front_rig().pivot, {0.0f, 0.0f, 0.0f});
}

TEST(CameraControl, OrbitKeepsTheDistanceAndLooksAtThePivot) {
    const CameraRig rig = orbit(front_rig(), {120.0f, -45.0f});
    EXPECT_NEAR(glm::length(rig.camera.position - rig.pivot), 5.0f, 1e-4f);
    expect_near(rig.camera.forward, glm::normalize(rig.pivot - rig.camera.position));
    expect_orthonormal_frame(rig.camera);
    EXPECT_NEAR(rig.camera.right.y, 0.0f, 1e-6f);   // the horizon stays level
}

TEST(CameraControl, OrbitRightTurnsTheCameraLeftByTheDragAngle) {
    // pi/2 radians of drag to the right: from +Z the camera goes to -X, looking along +X.
    const float pixels = (3.14159265f / 2.0f) / kOrbitRadiansPerPixel;
    const CameraRig rig = orbit(front_rig(), {pixels, 0.0f});
    expect_near(rig.camera.position, {-5.0f, 0.0f, 0.0f}, 1e-4f);
    expect_near(rig.camera.forward, {1.0f, 0.0f, 0.0f}, 1e-4f);
}

TEST(CameraControl, OrbitPitchStopsShortOfThePole) {
    const CameraRig rig = orbit(front_rig(), {0.0f, 1e6f});
    const float elevation = glm::degrees(std::asin(rig.camera.position.y / 5.0f));
    EXPECT_NEAR(elevation, kMaxPitchDegrees, 1e-3f);
    expect_orthonormal_frame(rig.camera);
}

TEST(CameraControl, ZeroDragChangesNothing) {
    const CameraRig a = front_rig();
    const CameraRig b = orbit(a, {0.0f, 0.0f});
    expect_near(b.camera.position, a.camera.position);
    expect_near(b.camera.forward, a.camera.forward);
    expect_near(b.camera.up, a.camera.up);
}

TEST(CameraControl, PanOfOneViewportHeightMovesByTheViewHeightAtThePivot) {
    const CameraRig a = front_rig();
    const CameraRig b = pan(a, {0.0f, 100.0f}, 100);   // drag down a whole viewport: the camera goes up
    const float height = 2.0f * 5.0f * std::tan(a.camera.yfov * 0.5f);
    expect_near(b.camera.position - a.camera.position, {0.0f, height, 0.0f}, 1e-4f);
    expect_near(b.pivot - a.pivot, {0.0f, height, 0.0f}, 1e-4f);
    expect_near(b.camera.forward, a.camera.forward);
}

TEST(CameraControl, ZoomStepsScaleTheDistanceAndUndoEachOther) {
    const CameraRig a = front_rig();
    const CameraRig in = zoom(a, 2.0f);
    EXPECT_NEAR(glm::length(in.camera.position - in.pivot), 5.0f * kZoomPerStep * kZoomPerStep, 1e-5f);
    expect_near(zoom(in, -2.0f).camera.position, a.camera.position, 1e-4f);
    EXPECT_GT(glm::length(zoom(a, 200.0f).camera.position - a.pivot), 0.0f);   // never through the pivot
}

TEST(CameraControl, ZoomOnAnOrthographicCameraShrinksTheView) {
    CameraRig a = front_rig();
    a.camera.projection = Projection::Orthographic;
    const CameraRig b = zoom(a, 1.0f);
    EXPECT_FLOAT_EQ(b.camera.ymag, a.camera.ymag * kZoomPerStep);
    expect_near(b.camera.position, a.camera.position);
}

TEST(CameraControl, MoveForwardAndRightFollowTheCameraFrame) {
    const CameraRig a = front_rig();
    const CameraRig b = move(a, {1.0f, 0.0f, 1.0f}, 2.0f);   // D + W
    expect_near(b.camera.position, {2.0f, 0.0f, 3.0f});
    expect_near(b.pivot - a.pivot, b.camera.position - a.camera.position);
}

}  // namespace
}  // namespace rt
