// The built-in scenes' registry (builtin_scenes.h) and the classic scenes: whitted, cornell, diffuse, dynamic,
// spheres:N and far. The rest live by purpose: builtin_room_scenes.cpp (mirror_box, office: stage 05's table),
// builtin_surface_scenes.cpp (material maps, cut-outs, absorption, normal maps); builtin_builders.h has the small
// builders they share. Units are metres, Y is up, light intensities are candela. Shading is Lambert
// kd / pi * I / d^2 * cos, so a point light at distance d lights a white surface facing it to about 1 when I = pi d^2;
// the intensities below aim a little under that so that little of the image clips.
#include "builtin_scenes.h"

#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "builtin_builders.h"
#include "builtin_room_scenes.h"
#include "builtin_surface_scenes.h"
#include "common/scene/gltf/gltf_io.h"

namespace rt {

namespace {

constexpr float kPi = 3.14159265358979f;

// Whitted (1980), "An improved illumination model for shaded display": a yellow/red checkerboard, a glass sphere in
// front of a mirror sphere, one light up and to the right so both shadows fall on the floor.
SceneAsset whitted() {
    SceneAsset a;
    a.name = "whitted";
    a.background = glm::vec3(0.2f, 0.3f, 0.5f);

    Texture checker;
    checker.name = "checker";
    checker.width = checker.height = 2;
    checker.nearest = true;
    const std::uint8_t yellow[4] = {255, 215, 0, 255}, red[4] = {215, 25, 20, 255};   // sRGB
    for (int i = 0; i < 4; ++i) {
        const std::uint8_t* c = (i == 0 || i == 3) ? yellow : red;
        for (int k = 0; k < 4; ++k) checker.rgba8.push_back(c[k]);
    }
    a.textures.push_back(checker);

    Material floor = diffuse("checkerboard", glm::vec3(1.0f));
    floor.base_color_texture = 0;
    const int floor_m = add_material(a, floor);
    const int glass_m = add_material(a, glass("glass"));
    const int mirror_m = add_material(a, mirror("mirror", glm::vec3(0.9f)));

    // 8 m x 8 m floor; the 2x2 texture repeats 4 times: 8 x 8 checks of 1 m.
    add_mesh_node(a, "floor", make_quad({0, 0, -2}, {4, 0, 0}, {0, 0, -4}, 4.0f, floor_m));
    add_mesh_node(a, "glass sphere", make_uv_sphere({0.5f, 1.1f, 0.3f}, 0.8f, 48, 24, glass_m));
    add_mesh_node(a, "mirror sphere", make_uv_sphere({-1.0f, 1.0f, -1.8f}, 1.0f, 48, 24, mirror_m));

    add_camera(a, {0.0f, 2.2f, 5.5f}, {-0.2f, 0.9f, -0.6f}, 45.0f);
    // 6.4 m from the nearest floor check (2, 0, 1), where a white floor would shade to 130 / pi / 41 * 0.94 ~ 0.94;
    // under the glass sphere (7.3 m away) it shades to ~0.63.
    add_point_light(a, {3.0f, 6.0f, 3.0f}, 130.0f);
    return a;
}

// A 2 m Cornell box open at the front (z = +1), with a tall mirror block and a glass sphere.
SceneAsset cornell() {
    SceneAsset a;
    a.name = "cornell";
    a.background = glm::vec3(0.02f, 0.02f, 0.03f);
    const int white = add_material(a, diffuse("white", glm::vec3(0.75f)));
    const int red = add_material(a, diffuse("red", glm::vec3(0.65f, 0.06f, 0.05f)));
    const int green = add_material(a, diffuse("green", glm::vec3(0.12f, 0.45f, 0.15f)));
    const int mirror_m = add_material(a, mirror("mirror", glm::vec3(0.9f)));
    const int glass_m = add_material(a, glass("glass"));

    // Walls as quads with inward normals (cross(u, v) points into the box).
    add_mesh_node(a, "floor", make_quad({0, 0, 0}, {1, 0, 0}, {0, 0, -1}, 1.0f, white));
    add_mesh_node(a, "ceiling", make_quad({0, 2, 0}, {1, 0, 0}, {0, 0, 1}, 1.0f, white));
    add_mesh_node(a, "back wall", make_quad({0, 1, -1}, {1, 0, 0}, {0, 1, 0}, 1.0f, white));
    add_mesh_node(a, "left wall", make_quad({-1, 1, 0}, {0, 0, -1}, {0, 1, 0}, 1.0f, red));
    add_mesh_node(a, "right wall", make_quad({1, 1, 0}, {0, 0, 1}, {0, 1, 0}, 1.0f, green));

    // The tall block, turned 30 degrees about its vertical axis so that its faces mirror the coloured walls.
    Node block;
    block.name = "mirror block";
    block.mesh = add_mesh(a, "mirror block", make_box({-0.28f, 0.0f, -0.28f}, {0.28f, 1.2f, 0.28f}, mirror_m));
    block.translation = {-0.4f, 0.0f, -0.35f};
    block.rotation = glm::angleAxis(glm::radians(-30.0f), glm::vec3(0, 1, 0));
    add_node(a, block);
    add_mesh_node(a, "glass sphere", make_uv_sphere({0.4f, 0.35f, 0.3f}, 0.35f, 48, 24, glass_m));

    add_camera(a, {0.0f, 1.0f, 3.4f}, {0.0f, 1.0f, 0.0f}, 40.0f);
    // Half a metre under the ceiling: the floor centre shades to 0.75 / pi * 4.5 / 1.5^2 ~ 0.48, the back wall centre
    // to ~0.77; the ceiling right above the light is a hot spot (radius ~0.65 m), as with any point light near a wall.
    add_point_light(a, {0.0f, 1.5f, 0.0f}, 4.5f);
    return a;
}

// Diffuse surfaces only: a floor, two boxes and two spheres, one light.
void add_diffuse_set(SceneAsset& a) {
    const int floor_m = add_material(a, diffuse("floor", glm::vec3(0.7f)));
    const int red = add_material(a, diffuse("red", glm::vec3(0.7f, 0.15f, 0.1f)));
    const int blue = add_material(a, diffuse("blue", glm::vec3(0.15f, 0.25f, 0.7f)));
    const int yellow = add_material(a, diffuse("yellow", glm::vec3(0.8f, 0.65f, 0.15f)));
    const int green = add_material(a, diffuse("green", glm::vec3(0.2f, 0.6f, 0.25f)));
    add_mesh_node(a, "floor", make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, 5.0f, floor_m));
    add_mesh_node(a, "red sphere", make_uv_sphere({-1.2f, 0.7f, 0.0f}, 0.7f, 48, 24, red));
    add_mesh_node(a, "blue box", make_box({0.2f, 0.0f, -1.2f}, {1.2f, 1.0f, -0.2f}, blue));
    add_mesh_node(a, "yellow sphere", make_uv_sphere({1.3f, 0.4f, 0.9f}, 0.4f, 32, 16, yellow));
    add_mesh_node(a, "green box", make_box({-0.3f, 0.0f, 0.6f}, {0.3f, 0.6f, 1.2f}, green));
}

SceneAsset diffuse_scene() {
    SceneAsset a;
    a.name = "diffuse";
    a.background = glm::vec3(0.25f, 0.3f, 0.4f);
    add_diffuse_set(a);
    add_camera(a, {0.0f, 2.5f, 6.0f}, {0.0f, 0.5f, 0.0f}, 45.0f);
    // ~5.8 m from the scene centre: pi * 5.8^2 ~ 106.
    add_point_light(a, {2.5f, 5.0f, 3.0f}, 100.0f);
    return a;
}

// The diffuse set plus a bouncing sphere (LINEAR translation), a turning box (LINEAR rotation) and a mirror sphere.
// The animation lasts 2 s; flatten clamps beyond it.
SceneAsset dynamic() {
    SceneAsset a;
    a.name = "dynamic";
    a.background = glm::vec3(0.25f, 0.3f, 0.4f);
    add_diffuse_set(a);
    const int orange = add_material(a, diffuse("orange", glm::vec3(0.9f, 0.45f, 0.1f)));
    const int purple = add_material(a, diffuse("purple", glm::vec3(0.5f, 0.2f, 0.6f)));
    const int mirror_m = add_material(a, mirror("mirror", glm::vec3(0.9f)));
    add_mesh_node(a, "mirror sphere", make_uv_sphere({2.2f, 0.6f, -1.6f}, 0.6f, 48, 24, mirror_m));

    Node ball;
    ball.name = "bouncing sphere";
    ball.mesh = add_mesh(a, "bouncing sphere", make_uv_sphere({0, 0, 0}, 0.35f, 32, 16, orange));
    ball.translation = {-0.2f, 1.8f, 1.9f};
    const int ball_node = add_node(a, ball);

    Node box;
    box.name = "turning box";
    box.mesh = add_mesh(a, "turning box", make_box({-0.35f, 0.0f, -0.35f}, {0.35f, 0.7f, 0.35f}, purple));
    box.translation = {-1.8f, 0.0f, 1.5f};
    const int box_node = add_node(a, box);

    Animation anim;
    anim.name = "motion";
    AnimationChannel bounce;
    bounce.node = ball_node;
    bounce.path = AnimationPath::Translation;
    bounce.interpolation = Interpolation::Linear;
    bounce.times = {0.0f, 0.5f, 1.0f, 1.5f, 2.0f};
    for (float y : {1.8f, 0.35f, 1.8f, 0.35f, 1.8f}) bounce.values.push_back(glm::vec4(-0.2f, y, 1.9f, 0.0f));
    anim.channels.push_back(bounce);

    AnimationChannel turn;
    turn.node = box_node;
    turn.path = AnimationPath::Rotation;
    turn.interpolation = Interpolation::Linear;
    // A full turn about Y in quarter steps (slerp between keys 90 degrees apart).
    for (int k = 0; k <= 4; ++k) {
        turn.times.push_back(0.5f * float(k));
        const glm::quat q = glm::angleAxis(0.5f * kPi * float(k), glm::vec3(0, 1, 0));
        turn.values.push_back(glm::vec4(q.x, q.y, q.z, q.w));
    }
    anim.channels.push_back(turn);
    a.animations.push_back(anim);

    add_camera(a, {0.0f, 2.5f, 6.0f}, {0.0f, 0.5f, 0.0f}, 45.0f);
    add_point_light(a, {2.5f, 5.0f, 3.0f}, 100.0f);
    return a;
}

// N spheres (radius 0.35, 1 m apart) on a square grid on a floor. The spheres share one mesh per colour and are
// placed by node translations.
SceneAsset spheres(int count) {
    SceneAsset a;
    a.name = "spheres:" + std::to_string(count);
    a.background = glm::vec3(0.25f, 0.3f, 0.4f);
    const int side = int(std::ceil(std::sqrt(float(count))));
    const float extent = float(side);   // metres covered by the grid
    const int floor_m = add_material(a, diffuse("floor", glm::vec3(0.7f)));
    const float half = 0.5f * extent + 1.0f;
    add_mesh_node(a, "floor", make_quad({0, 0, 0}, {half, 0, 0}, {0, 0, -half}, half, floor_m));

    const glm::vec3 colors[] = {{0.8f, 0.2f, 0.15f}, {0.2f, 0.6f, 0.25f}, {0.15f, 0.3f, 0.8f}, {0.85f, 0.7f, 0.15f},
                                {0.6f, 0.25f, 0.7f}, {0.15f, 0.65f, 0.7f}, {0.9f, 0.45f, 0.1f}, {0.75f, 0.75f, 0.75f}};
    int meshes[8];
    for (int i = 0; i < 8; ++i) {
        const int m = add_material(a, diffuse("colour " + std::to_string(i), colors[i]));
        meshes[i] = add_mesh(a, "sphere " + std::to_string(i), make_uv_sphere({0, 0, 0}, 0.35f, 16, 8, m));
    }
    for (int i = 0; i < count; ++i) {
        const int row = i / side, col = i % side;
        Node n;
        n.name = "sphere " + std::to_string(i);
        n.mesh = meshes[(row * 3 + col) % 8];
        n.translation = {float(col) - 0.5f * float(side - 1), 0.36f, float(row) - 0.5f * float(side - 1)};
        add_node(a, n);
    }

    // Frame the grid from the front and above; the light hangs above the front right.
    // The grid's half diagonal must fit in half the vertical field of view (22.5 degrees) seen from the distance d
    // along normalize(0, 0.8, 1); seen at that slant the square looks flatter, so tan rather than sin leaves a margin.
    const float radius = 0.5f * std::sqrt(2.0f) * extent + 0.5f;
    const glm::vec3 eye = glm::normalize(glm::vec3(0.0f, 0.8f, 1.0f)) * (radius / std::tan(glm::radians(22.5f)));
    add_camera(a, eye, {0.0f, 0.0f, 0.0f}, 45.0f);
    const glm::vec3 light = glm::vec3(0.3f, 1.0f, 0.6f) * (extent + 3.0f);
    add_point_light(a, light, 0.8f * kPi * glm::dot(light, light));
    return a;
}

// Whitted's scene with everything under one root translated by (1e4, 1e4, 1e4).
SceneAsset far() {
    SceneAsset a = whitted();
    a.name = "far";
    Node root;
    root.name = "far away";
    root.translation = glm::vec3(1e4f);
    root.children = a.roots;
    a.roots.clear();
    add_node(a, root);
    return a;
}

int parse_sphere_count(const std::string& text) {
    if (text.empty() || text.size() > 5) throw SceneError("bad sphere count '" + text + "' (expected 1 to 10000)");
    int n = 0;
    for (char c : text) {
        if (c < '0' || c > '9') throw SceneError("bad sphere count '" + text + "' (expected 1 to 10000)");
        n = n * 10 + (c - '0');
    }
    if (n < 1 || n > 10000) throw SceneError("bad sphere count '" + text + "' (expected 1 to 10000)");
    return n;
}

}  // namespace


std::vector<std::string> builtin_scene_names() {
    return {"whitted", "cornell", "diffuse", "dynamic", "spheres", "far", "mirror_box", "office", "office_soft",
            "material_maps", "absorption", "normal_map", "cutouts", "soft_shadows"};
}

std::string builtin_scene_list() {
    std::string known;
    for (const std::string& n : builtin_scene_names()) known += (known.empty() ? "" : ", ") + n;
    return known + "; spheres takes a count, spheres:N";
}

SceneAsset make_builtin_scene(const std::string& name) {
    if (name == "whitted") return whitted();
    if (name == "cornell") return cornell();
    if (name == "diffuse") return diffuse_scene();
    if (name == "dynamic") return dynamic();
    if (name == "far") return far();
    if (name == "mirror_box") return mirror_box_scene();
    if (name == "office") return office_scene();
    if (name == "office_soft") return office_soft_scene();
    if (name == "soft_shadows") return soft_shadows_scene();
    if (name == "material_maps") return material_maps_scene();
    if (name == "absorption") return absorption_scene();
    if (name == "normal_map") return normal_map_scene();
    if (name == "cutouts") return cutouts_scene();
    if (name == "spheres") return spheres(64);
    if (name.rfind("spheres:", 0) == 0) return spheres(parse_sphere_count(name.substr(8)));
    throw SceneError("unknown built-in scene '" + name + "' (known: " + builtin_scene_list() + ")");
}

}  // namespace rt
