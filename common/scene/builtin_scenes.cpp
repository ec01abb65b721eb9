// The procedural scenes. Units are metres, Y is up, light intensities are candela. Shading is Lambert
// kd / pi * I / d^2 * cos, so a point light at distance d lights a white surface facing it to about 1 when I = pi d^2;
// the intensities below aim a little under that so that little of the image clips.
#include "builtin_scenes.h"

#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "builtin_builders.h"
#include "builtin_surface_scenes.h"
#include "gltf_io.h"

namespace rt {

namespace {

constexpr float kPi = 3.14159265358979f;

// ---------------------------------------------------------------------------------------------------------------
// Small builders.

Material diffuse(const std::string& name, glm::vec3 color) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(color, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

Material mirror(const std::string& name, glm::vec3 color) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(color, 1.0f);
    m.metallic = 1.0f;
    m.roughness = 0.0f;
    return m;
}

Material glass(const std::string& name) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(1.0f);
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.transmission = 1.0f;
    m.ior = 1.5f;
    return m;
}

// A mesh of one primitive; returns the mesh index.
int add_mesh(SceneAsset& a, const std::string& name, Primitive p) {
    Mesh m;
    m.name = name;
    m.primitives.push_back(std::move(p));
    a.meshes.push_back(std::move(m));
    return int(a.meshes.size() - 1);
}

// Appends a node (a root when `root`); returns its index.
int add_node(SceneAsset& a, Node n, bool root = true) {
    a.nodes.push_back(std::move(n));
    const int index = int(a.nodes.size() - 1);
    if (root) a.roots.push_back(index);
    return index;
}

// Rotation that turns a glTF camera (looking down -Z, +Y up) to look from eye at target.
glm::quat look_rotation(const glm::vec3& eye, const glm::vec3& target) {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    return glm::normalize(glm::quat_cast(glm::mat3(right, up, -forward)));
}

void add_camera(SceneAsset& a, const glm::vec3& eye, const glm::vec3& target, float yfov_degrees) {
    Camera c;
    c.name = "camera";
    c.yfov = glm::radians(yfov_degrees);
    c.znear = 0.01f;
    a.cameras.push_back(c);
    Node n;
    n.name = "camera";
    n.camera = int(a.cameras.size() - 1);
    n.translation = eye;
    n.rotation = look_rotation(eye, target);
    add_node(a, n);
}

void add_point_light(SceneAsset& a, const glm::vec3& position, float intensity) {
    Light l;
    l.name = "light";
    l.type = LightType::Point;
    l.intensity = intensity;
    a.lights.push_back(l);
    Node n;
    n.name = "light";
    n.light = int(a.lights.size() - 1);
    n.translation = position;
    add_node(a, n);
}

// ---------------------------------------------------------------------------------------------------------------
// The scenes.

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
        checker.rgba8.insert(checker.rgba8.end(), c, c + 4);
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

// The six walls of the box lo..hi as quads facing inward (cross(u, v) points into the box), one material each:
// floor, ceiling, back (-z), front (+z), left (-x), right (+x).
void add_room(SceneAsset& a, const glm::vec3& lo, const glm::vec3& hi, const int (&materials)[6]) {
    const glm::vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
    add_mesh_node(a, "floor", make_quad({c.x, lo.y, c.z}, {h.x, 0, 0}, {0, 0, -h.z}, 1.0f, materials[0]));
    add_mesh_node(a, "ceiling", make_quad({c.x, hi.y, c.z}, {h.x, 0, 0}, {0, 0, h.z}, 1.0f, materials[1]));
    add_mesh_node(a, "back wall", make_quad({c.x, c.y, lo.z}, {h.x, 0, 0}, {0, h.y, 0}, 1.0f, materials[2]));
    add_mesh_node(a, "front wall", make_quad({c.x, c.y, hi.z}, {-h.x, 0, 0}, {0, h.y, 0}, 1.0f, materials[3]));
    add_mesh_node(a, "left wall", make_quad({lo.x, c.y, c.z}, {0, 0, -h.z}, {0, h.y, 0}, 1.0f, materials[4]));
    add_mesh_node(a, "right wall", make_quad({hi.x, c.y, c.z}, {0, 0, h.z}, {0, h.y, 0}, 1.0f, materials[5]));
}

// A ball of small cubes: the cells of a 5 x 5 x 5 grid (pitch `pitch`) within 2.3 cells of the centre, as one
// primitive of 57 boxes (684 triangles). Flat faces: no shadow-terminator steps as on a coarse smooth sphere.
Primitive make_cube_ball(const glm::vec3& center, float pitch, int material) {
    Primitive ball;
    ball.material = material;
    for (int x = -2; x <= 2; ++x)
        for (int y = -2; y <= 2; ++y)
            for (int z = -2; z <= 2; ++z) {
                if (x * x + y * y + z * z > 5.29f) continue;
                const glm::vec3 c = center + pitch * glm::vec3(x, y, z);
                const Primitive box = make_box(c - 0.4f * pitch, c + 0.4f * pitch, material);
                const auto base = std::uint32_t(ball.positions.size());
                ball.positions.insert(ball.positions.end(), box.positions.begin(), box.positions.end());
                ball.normals.insert(ball.normals.end(), box.normals.begin(), box.normals.end());
                ball.uvs.insert(ball.uvs.end(), box.uvs.begin(), box.uvs.end());
                for (std::uint32_t i : box.indices) ball.indices.push_back(base + i);
            }
    return ball;
}

// Reis's reflection-heavy scene: an object of several hundred triangles (make_cube_ball) inside a closed box of six
// mirrors, lit by one light; the camera is inside too. Mirrors of slightly different tints tell the reflections apart.
SceneAsset mirror_box() {
    SceneAsset a;
    a.name = "mirror_box";
    a.background = glm::vec3(0.02f, 0.02f, 0.03f);   // seen only where a path ends on its depth limit
    const int object = add_material(a, diffuse("orange", glm::vec3(0.85f, 0.4f, 0.12f)));
    const int floor_m = add_material(a, mirror("floor mirror", glm::vec3(0.8f, 0.8f, 0.8f)));
    const int warm = add_material(a, mirror("warm mirror", glm::vec3(0.9f, 0.8f, 0.7f)));
    const int cool = add_material(a, mirror("cool mirror", glm::vec3(0.7f, 0.8f, 0.9f)));
    const int plain = add_material(a, mirror("mirror", glm::vec3(0.85f)));
    add_room(a, {-1.5f, 0.0f, -1.5f}, {1.5f, 3.0f, 1.5f}, {floor_m, plain, plain, plain, warm, cool});
    add_mesh_node(a, "object", make_cube_ball({0.0f, 1.2f, -0.2f}, 0.22f, object));
    add_camera(a, {0.9f, 2.0f, 1.3f}, {0.0f, 1.2f, -0.2f}, 60.0f);
    // 1.6 m above the object's top: pi * 1.6^2 ~ 8.
    add_point_light(a, {-0.6f, 2.7f, 0.6f}, 7.0f);
    return a;
}

// Office furniture, each part its own mesh (the scene has many meshes, as Reis's office does).
struct OfficeMaterials {
    int wood, metal, black, fabric, screen, ceramic, lamp, paper[4], leaf, pot, globe;
};

void add_desk(SceneAsset& a, const OfficeMaterials& m, const glm::vec3& p, int n) {
    const std::string id = " " + std::to_string(n);
    add_mesh_node(a, "desk top" + id, make_box(p + glm::vec3(-0.7f, 0.72f, -0.35f), p + glm::vec3(0.7f, 0.76f, 0.35f), m.wood));
    for (float x : {-0.65f, 0.62f})
        for (float z : {-0.3f, 0.27f})
            add_mesh_node(a, "desk leg" + id, make_box(p + glm::vec3(x, 0.0f, z), p + glm::vec3(x + 0.03f, 0.72f, z + 0.03f), m.metal));
    add_mesh_node(a, "monitor" + id, make_box(p + glm::vec3(-0.3f, 0.9f, -0.25f), p + glm::vec3(0.3f, 1.25f, -0.22f), m.screen));
    add_mesh_node(a, "monitor stand" + id, make_box(p + glm::vec3(-0.03f, 0.76f, -0.27f), p + glm::vec3(0.03f, 0.9f, -0.23f), m.black));
    add_mesh_node(a, "keyboard" + id, make_box(p + glm::vec3(-0.22f, 0.76f, -0.02f), p + glm::vec3(0.22f, 0.78f, 0.12f), m.black));
    add_mesh_node(a, "mug" + id, make_uv_sphere(p + glm::vec3(0.45f, 0.81f, 0.05f), 0.05f, 24, 12, m.ceramic));
    add_mesh_node(a, "lamp arm" + id, make_box(p + glm::vec3(-0.6f, 0.76f, -0.25f), p + glm::vec3(-0.58f, 1.1f, -0.23f), m.metal));
    add_mesh_node(a, "lamp head" + id, make_uv_sphere(p + glm::vec3(-0.55f, 1.12f, -0.2f), 0.08f, 32, 16, m.lamp));
    // The chair in front of the desk: seat, back, four legs.
    const glm::vec3 c = p + glm::vec3(0.0f, 0.0f, 0.65f);
    add_mesh_node(a, "chair seat" + id, make_box(c + glm::vec3(-0.24f, 0.44f, -0.22f), c + glm::vec3(0.24f, 0.5f, 0.22f), m.fabric));
    add_mesh_node(a, "chair back" + id, make_box(c + glm::vec3(-0.24f, 0.5f, 0.18f), c + glm::vec3(0.24f, 0.95f, 0.23f), m.fabric));
    for (float x : {-0.22f, 0.19f})
        for (float z : {-0.2f, 0.17f})
            add_mesh_node(a, "chair leg" + id, make_box(c + glm::vec3(x, 0.0f, z), c + glm::vec3(x + 0.03f, 0.44f, z + 0.03f), m.metal));
}

// A bookshelf against the back wall: four boards of 25 books each.
void add_bookshelf(SceneAsset& a, const OfficeMaterials& m, float x0, float back_z) {
    for (int board = 0; board < 4; ++board) {
        const float y = 0.05f + 0.5f * float(board);
        add_mesh_node(a, "shelf board", make_box({x0, y - 0.03f, back_z}, {x0 + 1.6f, y, back_z + 0.35f}, m.wood));
        float x = x0 + 0.03f;
        for (int book = 0; book < 25; ++book) {
            const float width = 0.035f + 0.02f * float((book * 7 + board * 3) % 4);
            const float height = 0.28f + 0.04f * float((book * 5 + board) % 3);
            add_mesh_node(a, "book", make_box({x, y, back_z + 0.04f}, {x + width, y + height, back_z + 0.3f},
                                              m.paper[(book + board) % 4]));
            x += width + 0.005f;
        }
    }
    for (float x : {x0, x0 + 1.57f})
        add_mesh_node(a, "shelf side", make_box({x, 0.0f, back_z}, {x + 0.03f, 1.6f, back_z + 0.35f}, m.wood));
}

// Reis's shadow-heavy scene: a furnished room (six desks with chairs, monitors, lamps and mugs, two bookshelves,
// four plants, a globe): 25,424 triangles in 330 meshes, diffuse only, one light under the ceiling.
SceneAsset office() {
    SceneAsset a;
    a.name = "office";
    a.background = glm::vec3(0.02f, 0.02f, 0.03f);   // a closed room: never seen
    OfficeMaterials m;
    m.wood = add_material(a, diffuse("wood", glm::vec3(0.55f, 0.38f, 0.22f)));
    m.metal = add_material(a, diffuse("metal", glm::vec3(0.6f)));
    m.black = add_material(a, diffuse("black", glm::vec3(0.05f)));
    m.fabric = add_material(a, diffuse("fabric", glm::vec3(0.15f, 0.25f, 0.55f)));
    m.screen = add_material(a, diffuse("screen", glm::vec3(0.1f, 0.12f, 0.15f)));
    m.ceramic = add_material(a, diffuse("ceramic", glm::vec3(0.9f, 0.9f, 0.85f)));
    m.lamp = add_material(a, diffuse("lamp", glm::vec3(0.85f, 0.2f, 0.1f)));
    const glm::vec3 paper[4] = {{0.7f, 0.15f, 0.1f}, {0.15f, 0.35f, 0.6f}, {0.8f, 0.7f, 0.3f}, {0.2f, 0.5f, 0.25f}};
    for (int i = 0; i < 4; ++i) m.paper[i] = add_material(a, diffuse("book " + std::to_string(i), paper[i]));
    m.leaf = add_material(a, diffuse("leaves", glm::vec3(0.15f, 0.45f, 0.12f)));
    m.pot = add_material(a, diffuse("pot", glm::vec3(0.6f, 0.3f, 0.2f)));
    m.globe = add_material(a, diffuse("globe", glm::vec3(0.2f, 0.45f, 0.7f)));
    const int wall = add_material(a, diffuse("wall", glm::vec3(0.8f, 0.78f, 0.72f)));
    const int carpet = add_material(a, diffuse("carpet", glm::vec3(0.35f, 0.33f, 0.3f)));
    const int ceiling = add_material(a, diffuse("ceiling", glm::vec3(0.9f)));
    add_room(a, {-5.0f, 0.0f, -4.0f}, {5.0f, 3.0f, 4.0f}, {carpet, ceiling, wall, wall, wall, wall});

    int n = 0;
    for (float z : {-1.6f, 1.0f})
        for (float x : {-3.0f, 0.0f, 3.0f}) add_desk(a, m, {x, 0.0f, z}, n++);
    add_bookshelf(a, m, -4.5f, -4.0f);
    add_bookshelf(a, m, 2.9f, -4.0f);
    for (const glm::vec3& p : {glm::vec3(-4.5f, 0, 3.4f), glm::vec3(4.5f, 0, 3.4f), glm::vec3(-1.5f, 0, -3.5f),
                               glm::vec3(1.5f, 0, -3.5f)}) {
        add_mesh_node(a, "plant pot", make_box(p + glm::vec3(-0.2f, 0.0f, -0.2f), p + glm::vec3(0.2f, 0.4f, 0.2f), m.pot));
        add_mesh_node(a, "plant", make_uv_sphere(p + glm::vec3(0.0f, 0.8f, 0.0f), 0.4f, 48, 24, m.leaf));
    }
    add_mesh_node(a, "cabinet", make_box({4.2f, 0.0f, -1.0f}, {4.9f, 0.9f, 0.0f}, m.wood));
    add_mesh_node(a, "globe", make_uv_sphere({4.55f, 1.2f, -0.5f}, 0.3f, 64, 32, m.globe));

    add_camera(a, {4.2f, 1.9f, 3.6f}, {-1.0f, 0.7f, -1.5f}, 60.0f);
    // Under the ceiling's centre, ~3 m from the desks: pi * 3^2 ~ 28.
    add_point_light(a, {0.0f, 2.8f, 0.0f}, 24.0f);
    return a;
}

// Textures that scale material factors texel by texel, as exported models use them (Avocado, LightsPunctualLamp):
// a floor whose metallicRoughnessTexture alternates polished metal and rough plastic checks (factors metallic 1,
// roughness 1: without the texture, a rough metal that mirrors nothing), and a wall panel whose emissiveTexture draws
// coloured stripes. A diffuse ball stands on the floor so the metal checks have something to reflect.
SceneAsset material_maps() {
    SceneAsset a;
    a.name = "material_maps";
    a.background = glm::vec3(0.1f, 0.12f, 0.16f);

    Texture checks;   // linear bytes: green = roughness, blue = metallic
    checks.name = "metallic-roughness checks";
    checks.width = checks.height = 2;
    checks.nearest = true;
    const std::uint8_t polished_metal[4] = {0, 0, 255, 255}, rough_plastic[4] = {0, 255, 0, 255};
    for (int i = 0; i < 4; ++i) {
        const std::uint8_t* c = (i == 0 || i == 3) ? polished_metal : rough_plastic;
        checks.rgba8.insert(checks.rgba8.end(), c, c + 4);
    }
    a.textures.push_back(checks);
    Texture stripes;   // sRGB colours, bilinear
    stripes.name = "emissive stripes";
    stripes.width = 4;
    stripes.height = 1;
    stripes.rgba8 = {255, 60, 20, 255, 255, 200, 40, 255, 30, 200, 255, 255, 0, 0, 0, 255};
    a.textures.push_back(stripes);

    Material floor = diffuse("checked floor", glm::vec3(0.8f));
    floor.metallic = 1.0f;
    floor.roughness = 1.0f;
    floor.metallic_roughness_texture = 0;
    Material panel = diffuse("glowing panel", glm::vec3(0.05f));
    panel.emissive = glm::vec3(1.5f);
    panel.emissive_texture = 1;
    const int floor_m = add_material(a, floor);
    const int panel_m = add_material(a, panel);
    const int ball_m = add_material(a, diffuse("ball", glm::vec3(0.2f, 0.5f, 0.8f)));

    add_mesh_node(a, "floor", make_quad({0, 0, -1}, {3, 0, 0}, {0, 0, -3}, 2.0f, floor_m));
    add_mesh_node(a, "panel", make_quad({0, 1.2f, -3.5f}, {2.5f, 0, 0}, {0, 1.0f, 0}, 1.0f, panel_m));
    add_mesh_node(a, "ball", make_uv_sphere({0.4f, 0.6f, -0.6f}, 0.6f, 24, 12, ball_m));
    add_camera(a, {0.0f, 2.0f, 4.0f}, {0.0f, 0.6f, -1.0f}, 45.0f);
    add_point_light(a, {2.0f, 4.0f, 2.0f}, 60.0f);
    return a;
}

// Alpha cut-outs (docs/shading.md, "Alpha: cut-outs and blending"): a green fence quad whose texture has round holes
// (alphaMode MASK, bilinear alpha, cutoff 0.5) in front of a lit wall, so its shadow shows the holes; a mirror on the
// right that reflects the fence, holes and all; a BLEND pane at the left with see-through stripes (alpha 0.3 in a
// nearest texture: read as cut out, below 0.5).
SceneAsset cutouts() {
    SceneAsset a;
    a.name = "cutouts";
    a.background = glm::vec3(0.25f, 0.3f, 0.4f);

    Texture holes;   // 16 x 16, a round hole of radius 1.5 texels in each 4 x 4 block
    holes.name = "fence holes";
    holes.width = holes.height = 16;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const float dx = float(x % 4) - 1.5f, dy = float(y % 4) - 1.5f;
            const std::uint8_t alpha = dx * dx + dy * dy < 1.5f * 1.5f ? 0 : 255;
            const std::uint8_t texel[4] = {70, 170, 60, alpha};   // sRGB green
            holes.rgba8.insert(holes.rgba8.end(), texel, texel + 4);
        }
    a.textures.push_back(holes);
    Texture stripes;   // 4 x 1, nearest: two opaque texels, two at alpha 80 / 255 ~ 0.31
    stripes.name = "pane stripes";
    stripes.width = 4;
    stripes.height = 1;
    stripes.nearest = true;
    for (int x = 0; x < 4; ++x) {
        const std::uint8_t texel[4] = {90, 140, 230, std::uint8_t(x < 2 ? 255 : 80)};
        stripes.rgba8.insert(stripes.rgba8.end(), texel, texel + 4);
    }
    a.textures.push_back(stripes);

    Material fence = diffuse("fence", glm::vec3(1.0f));
    fence.base_color_texture = 0;
    fence.alpha_mode = AlphaMode::Mask;
    fence.alpha_cutoff = 0.5f;
    Material pane = diffuse("pane", glm::vec3(1.0f));
    pane.base_color_texture = 1;
    pane.alpha_mode = AlphaMode::Blend;
    const int fence_m = add_material(a, fence);
    const int pane_m = add_material(a, pane);
    const int wall_m = add_material(a, diffuse("wall", glm::vec3(0.8f, 0.78f, 0.72f)));
    const int floor_m = add_material(a, diffuse("floor", glm::vec3(0.45f, 0.42f, 0.38f)));
    const int mirror_m = add_material(a, mirror("mirror", glm::vec3(0.9f)));

    add_mesh_node(a, "floor", make_quad({0, 0, 0.5f}, {5, 0, 0}, {0, 0, -3}, 1.0f, floor_m));
    add_mesh_node(a, "wall", make_quad({0, 2, -2.5f}, {5, 0, 0}, {0, 2, 0}, 1.0f, wall_m));
    // 1.8 m x 1.8 m, the texture twice across: 8 x 8 holes of about 0.11 m.
    add_mesh_node(a, "fence", make_quad({-0.3f, 1.1f, -0.6f}, {0.9f, 0, 0}, {0, 0.9f, 0}, 2.0f, fence_m));
    add_mesh_node(a, "pane", make_quad({-1.6f, 0.8f, 1.0f}, {0.45f, 0, 0.2f}, {0, 0.7f, 0}, 2.0f, pane_m));
    // Facing (-0.92, 0, 0.39): the camera sees the fence in it.
    add_mesh_node(a, "mirror", make_quad({2.0f, 1.1f, 0.2f}, {0.23f, 0, 0.55f}, {0, 0.8f, 0}, 1.0f, mirror_m));

    add_camera(a, {0.0f, 1.5f, 4.5f}, {0.1f, 1.0f, -1.0f}, 50.0f);
    add_point_light(a, {-0.8f, 3.0f, 2.5f}, 60.0f);
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

// The builders builtin_builders.h shares with the other built-in scene files.

int add_material(SceneAsset& a, const Material& m) {
    a.materials.push_back(m);
    return int(a.materials.size() - 1);
}

int add_mesh_node(SceneAsset& a, const std::string& name, Primitive p) {
    Node n;
    n.name = name;
    n.mesh = add_mesh(a, name, std::move(p));
    return add_node(a, n);
}

// A quad centred at c spanning c +- u +- v, facing cross(u, v), indexed; uv from (0,0) to (uv_scale, uv_scale).
Primitive make_quad(const glm::vec3& c, const glm::vec3& u, const glm::vec3& v, float uv_scale, int material) {
    Primitive p;
    p.material = material;
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    p.positions = {c - u - v, c + u - v, c + u + v, c - u + v};
    p.normals = {n, n, n, n};
    p.uvs = {{0, uv_scale}, {uv_scale, uv_scale}, {uv_scale, 0}, {0, 0}};
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

std::vector<std::string> builtin_scene_names() {
    return {"whitted", "cornell", "diffuse", "dynamic", "spheres", "far", "mirror_box", "office", "material_maps",
            "absorption", "normal_map", "cutouts"};
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
    if (name == "mirror_box") return mirror_box();
    if (name == "office") return office();
    if (name == "material_maps") return material_maps();
    if (name == "absorption") return absorption_scene();
    if (name == "normal_map") return normal_map_scene();
    if (name == "cutouts") return cutouts();
    if (name == "spheres") return spheres(64);
    if (name.rfind("spheres:", 0) == 0) return spheres(parse_sphere_count(name.substr(8)));
    throw SceneError("unknown built-in scene '" + name + "' (known: " + builtin_scene_list() + ")");
}

// A UV sphere: (segments + 1) columns x (rings + 1) rows of vertices, theta from the north pole (row 0) to the south
// pole, phi around +Y. The seam column repeats column 0 and every pole vertex repeats the exact pole position, so
// triangles meeting there share identical positions (the mesh is closed). At the poles only one triangle per segment
// is emitted (no degenerate ones).
Primitive make_uv_sphere(const glm::vec3& center, float radius, int segments, int rings, int material) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    Primitive p;
    p.material = material;
    const auto columns = std::uint32_t(segments + 1);
    for (int i = 0; i <= rings; ++i) {
        const float theta = kPi * float(i) / float(rings);
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * kPi * float(j % segments) / float(segments);
            glm::vec3 dir(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            if (i == 0) dir = glm::vec3(0, 1, 0);
            if (i == rings) dir = glm::vec3(0, -1, 0);
            p.positions.push_back(center + radius * dir);
            p.normals.push_back(dir);
            const float u = (i == 0 || i == rings) ? (float(j) + 0.5f) / float(segments) : float(j) / float(segments);
            p.uvs.push_back({u, float(i) / float(rings)});
        }
    }
    // Counter-clockwise seen from outside: a (row i, col j), c (row i+1, col j), d (i+1, j+1), b (i, j+1).
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t a = std::uint32_t(i) * columns + std::uint32_t(j), b = a + 1;
            const std::uint32_t c = a + columns, d = c + 1;
            if (i != rings - 1) p.indices.insert(p.indices.end(), {a, c, d});   // degenerate at the south pole
            if (i != 0) p.indices.insert(p.indices.end(), {a, d, b});           // degenerate at the north pole
        }
    }
    return p;
}

Primitive make_box(const glm::vec3& lo, const glm::vec3& hi, int material) {
    Primitive p;
    p.material = material;
    const glm::vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
    // Each face: outward normal n and in-plane axes u, v with cross(u, v) = n, so the quad is counter-clockwise.
    const glm::vec3 faces[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
        {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    for (const auto& f : faces) {
        const glm::vec3 n = f[0], u = f[1] * h, v = f[2] * h, fc = c + n * h;
        const auto base = std::uint32_t(p.positions.size());
        p.positions.insert(p.positions.end(), {fc - u - v, fc + u - v, fc + u + v, fc - u + v});
        p.normals.insert(p.normals.end(), {n, n, n, n});
        p.uvs.insert(p.uvs.end(), {{0, 1}, {1, 1}, {1, 0}, {0, 0}});
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return p;
}

}  // namespace rt
