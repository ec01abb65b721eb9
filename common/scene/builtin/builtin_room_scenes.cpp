// Built-in scenes shaped like the ray-hierarchy papers' test scenes (stage 05's table, docs/benchmarks.md): a
// closed box of mirrors around an object (reflection-heavy) and a furnished office (shadow-heavy).
#include "builtin_room_scenes.h"

#include <cmath>
#include <string>

#include "builtin_builders.h"
#include "builtin_scenes.h"

namespace rt {

namespace {

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

}  // namespace

// Reis's reflection-heavy scene: an object of several hundred triangles (make_cube_ball) inside a closed box of six
// mirrors, lit by one light; the camera is inside too. Mirrors of slightly different tints tell the reflections apart.
SceneAsset mirror_box_scene() {
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

namespace {

// Office furniture, each part its own mesh (the scene has many meshes, as Reis's office does).
struct OfficeMaterials {
    int wood, metal, black, fabric, screen, ceramic, lamp, paper[4], leaf, pot, globe;
};

void add_desk(SceneAsset& a, const OfficeMaterials& m, const glm::vec3& p, int n) {
    std::string id = " ";   // (not " " + to_string(n): GCC 12 warns falsely of an overlapping copy, -Wrestrict)
    id += std::to_string(n);
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

}  // namespace

// Reis's shadow-heavy scene: a furnished room (six desks with chairs, monitors, lamps and mugs, two bookshelves,
// four plants, a globe): 25,424 triangles in 330 meshes, diffuse only, one light under the ceiling.
namespace {

// The office without its light.
SceneAsset office_furniture(const std::string& name) {
    SceneAsset a;
    a.name = name;
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
    return a;
}

// A rectangular light just under a ceiling at height y, facing down: centre c, half extents hx (along x) and hz.
void add_ceiling_light(SceneAsset& a, const glm::vec3& c, float hx, float hz, const glm::vec3& radiance) {
    const int light = add_material(a, emitter("ceiling light", radiance));
    add_mesh_node(a, "ceiling light", make_quad(c, {hx, 0.0f, 0.0f}, {0.0f, 0.0f, hz}, 1.0f, light));
}

}  // namespace

SceneAsset office_scene() {
    SceneAsset a = office_furniture("office");
    // Under the ceiling's centre, ~3 m from the desks: pi * 3^2 ~ 28.
    add_point_light(a, {0.0f, 2.8f, 0.0f}, 24.0f);
    return a;
}

// The same room and point of view, lit by a 2 m x 1 m panel where the point light hung. Its power matches the point
// light's on the desks below (L A / d^2 ~ 24 / d^2 at d ~ 2.2 m: L = 12), so the two images compare.
SceneAsset office_soft_scene() {
    SceneAsset a = office_furniture("office_soft");
    add_ceiling_light(a, {0.0f, 2.99f, 0.0f}, 1.0f, 0.5f, glm::vec3(12.0f, 11.5f, 10.5f));
    return a;
}

// A 4 m x 3 m x 4 m room under a 1.2 m x 0.6 m ceiling light (radiance 18: about 0.5 on the floor below, a white
// Lambertian surface 3 m under 0.72 m^2). The pillar's shadow runs across the floor, sharp at its foot and wider
// further away; the ball's is dark where it touches the floor; the table's top casts an umbra ringed by penumbra.
SceneAsset soft_shadows_scene() {
    SceneAsset a;
    a.name = "soft_shadows";
    a.background = glm::vec3(0.02f, 0.02f, 0.03f);   // a closed room: never seen
    const int wall = add_material(a, diffuse("wall", glm::vec3(0.8f, 0.78f, 0.74f)));
    const int floor_m = add_material(a, diffuse("floor", glm::vec3(0.6f, 0.58f, 0.55f)));
    const int left = add_material(a, diffuse("left wall", glm::vec3(0.7f, 0.25f, 0.2f)));
    const int right = add_material(a, diffuse("right wall", glm::vec3(0.25f, 0.45f, 0.7f)));
    add_room(a, {-2.0f, 0.0f, -2.0f}, {2.0f, 3.0f, 2.0f}, {floor_m, wall, wall, wall, left, right});
    const int pillar = add_material(a, diffuse("pillar", glm::vec3(0.85f, 0.8f, 0.7f)));
    const int ball = add_material(a, diffuse("ball", glm::vec3(0.8f, 0.55f, 0.15f)));
    const int wood = add_material(a, diffuse("table", glm::vec3(0.5f, 0.33f, 0.2f)));
    add_mesh_node(a, "pillar", make_box({-1.25f, 0.0f, -1.1f}, {-0.95f, 1.8f, -0.8f}, pillar));
    add_mesh_node(a, "ball", make_uv_sphere({0.8f, 0.45f, -0.7f}, 0.45f, 32, 16, ball));
    add_mesh_node(a, "table top", make_box({-1.0f, 0.7f, 0.0f}, {-0.1f, 0.75f, 0.6f}, wood));
    for (float x : {-0.95f, -0.18f})
        for (float z : {0.05f, 0.52f})
            add_mesh_node(a, "table leg", make_box({x, 0.0f, z}, {x + 0.03f, 0.7f, z + 0.03f}, wood));
    add_ceiling_light(a, {0.0f, 2.99f, -0.3f}, 0.6f, 0.3f, glm::vec3(18.0f, 17.0f, 15.0f));
    add_camera(a, {1.1f, 1.45f, 1.9f}, {-0.3f, 1.25f, -1.0f}, 80.0f);
    return a;
}

}  // namespace rt
