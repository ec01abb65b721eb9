#include "builtin_surface_scenes.h"

#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "builtin_builders.h"
#include "builtin_scenes.h"

namespace rt {

namespace {

Material material(const std::string& name, glm::vec3 color, float metallic, float roughness) {
    Material m;
    m.name = name;
    m.base_color = glm::vec4(color, 1.0f);
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
}

void add_camera_and_light(SceneAsset& a, const glm::vec3& eye, const glm::vec3& target, const glm::vec3& light,
                          float intensity) {
    Camera c;
    c.name = "camera";
    c.yfov = glm::radians(45.0f);
    a.cameras.push_back(c);
    Node cn;
    cn.name = "camera";
    cn.camera = 0;
    cn.translation = eye;
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    cn.rotation = glm::normalize(glm::quat_cast(glm::mat3(right, glm::cross(right, forward), -forward)));
    a.nodes.push_back(cn);
    a.roots.push_back(int(a.nodes.size() - 1));
    Light l;
    l.name = "light";
    l.intensity = intensity;
    a.lights.push_back(l);
    Node ln;
    ln.name = "light";
    ln.light = 0;
    ln.translation = light;
    a.nodes.push_back(ln);
    a.roots.push_back(int(a.nodes.size() - 1));
}

// A 2x2 sRGB checker, nearest filtering.
Texture checker(const std::uint8_t (&a)[4], const std::uint8_t (&b)[4]) {
    Texture t;
    t.name = "checker";
    t.width = t.height = 2;
    t.nearest = true;
    for (int i = 0; i < 4; ++i) {
        const std::uint8_t* c = (i == 0 || i == 3) ? a : b;
        for (int k = 0; k < 4; ++k) t.rgba8.push_back(c[k]);
    }
    return t;
}

// A 32x32 tangent-space normal texture: one round bump (a spherical cap, radius 0.8 of the half cell) per texture,
// flat (0, 0, 1) around it. Texel rows go down the image (v grows), the map's +Y up it: y = -(row offset).
Texture bump_normals() {
    Texture t;
    t.name = "bumps";
    t.width = t.height = 32;
    for (int row = 0; row < 32; ++row)
        for (int col = 0; col < 32; ++col) {
            const float x = (float(col) + 0.5f) / 16.0f - 1.0f, y = -((float(row) + 0.5f) / 16.0f - 1.0f);
            const float r = 0.8f, d2 = x * x + y * y;
            glm::vec3 n(0.0f, 0.0f, 1.0f);
            if (d2 < r * r) n = glm::normalize(glm::vec3(x, y, std::sqrt(r * r - d2)));
            for (int k = 0; k < 3; ++k) t.rgba8.push_back(std::uint8_t(std::lround((n[k] * 0.5f + 0.5f) * 255.0f)));
            t.rgba8.push_back(255);
        }
    return t;
}

}  // namespace

SceneAsset absorption_scene() {
    SceneAsset a;
    a.name = "absorption";
    a.background = glm::vec3(0.6f, 0.65f, 0.7f);
    a.textures.push_back(checker({230, 230, 230, 255}, {40, 40, 40, 255}));
    Material checkered = material("checker", glm::vec3(1.0f), 0.0f, 1.0f);
    checkered.base_color_texture = 0;
    const int checker_m = add_material(a, checkered);
    // Blue-green glass: white light keeps (0.25, 0.65, 0.9) after 0.3 m inside.
    Material volume = material("absorbing glass", glm::vec3(1.0f), 0.0f, 0.0f);
    volume.transmission = 1.0f;
    volume.thickness = 1.0f;
    volume.attenuation_color = glm::vec3(0.25f, 0.65f, 0.9f);
    volume.attenuation_distance = 0.3f;
    const int volume_m = add_material(a, volume);
    Material thin = volume;
    thin.name = "thin-walled glass";
    thin.thickness = 0.0f;
    const int thin_m = add_material(a, thin);

    add_mesh_node(a, "floor", make_quad({0, 0, -1}, {4, 0, 0}, {0, 0, -3}, 6.0f, checker_m));
    add_mesh_node(a, "wall", make_quad({0, 2, -2.5f}, {4, 0, 0}, {0, 2, 0}, 4.0f, checker_m));
    const float depths[4] = {0.6f, 0.15f, 0.45f, 0.9f};
    for (int i = 0; i < 4; ++i) {
        const float x = -1.8f + 1.2f * float(i), d = depths[i];
        add_mesh_node(a, "slab " + std::to_string(i),
                      make_box({x - 0.45f, 0.02f, -0.5f * d}, {x + 0.45f, 1.22f, 0.5f * d}, i == 0 ? thin_m : volume_m));
    }
    add_camera_and_light(a, {0.0f, 1.6f, 4.2f}, {0.0f, 0.6f, -0.5f}, {1.5f, 4.0f, 3.0f}, 70.0f);
    return a;
}

SceneAsset normal_map_scene() {
    SceneAsset a;
    a.name = "normal_map";
    a.background = glm::vec3(0.25f, 0.3f, 0.4f);
    a.textures.push_back(bump_normals());
    Material wall = material("bumpy wall", glm::vec3(0.8f, 0.75f, 0.7f), 0.0f, 0.6f);
    wall.normal_texture = 0;
    const int wall_m = add_material(a, wall);
    Material floor = material("bumpy floor", glm::vec3(0.5f, 0.6f, 0.7f), 0.0f, 1.0f);
    floor.normal_texture = 0;
    floor.normal_scale = 0.7f;
    floor.normal_transform.rotation = 0.5f;
    floor.normal_transform.scale = {2.0f, 1.0f};
    floor.normal_transform.offset = {0.25f, 0.0f};
    const int floor_m = add_material(a, floor);
    Material ball = material("bumpy ball", glm::vec3(0.9f, 0.45f, 0.15f), 0.0f, 0.4f);
    ball.normal_texture = 0;
    ball.normal_transform.scale = {8.0f, 4.0f};
    const int ball_m = add_material(a, ball);
    const int mirror_m = add_material(a, material("mirror", glm::vec3(0.9f), 1.0f, 0.0f));

    Primitive wall_quad = make_quad({0, 1.5f, -2}, {3, 0, 0}, {0, 1.5f, 0}, 4.0f, wall_m);
    wall_quad.tangents.assign(4, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));   // given, as a glTF TANGENT attribute
    add_mesh_node(a, "wall", std::move(wall_quad));
    add_mesh_node(a, "floor", make_quad({0, 0, 0}, {3, 0, 0}, {0, 0, -2}, 3.0f, floor_m));
    add_mesh_node(a, "bumpy ball", make_uv_sphere({-0.9f, 0.7f, 0.0f}, 0.7f, 24, 12, ball_m));
    add_mesh_node(a, "mirror ball", make_uv_sphere({0.9f, 0.7f, 0.3f}, 0.7f, 24, 12, mirror_m));
    add_camera_and_light(a, {0.0f, 1.6f, 4.6f}, {0.0f, 0.9f, -0.5f}, {2.5f, 3.5f, 2.5f}, 55.0f);
    return a;
}

// Textures that scale material factors texel by texel, as exported models use them (Avocado, LightsPunctualLamp):
// a floor whose metallicRoughnessTexture alternates polished metal and rough plastic checks (factors metallic 1,
// roughness 1: without the texture, a rough metal that mirrors nothing), and a wall panel whose emissiveTexture draws
// coloured stripes. A diffuse ball stands on the floor so the metal checks have something to reflect.
SceneAsset material_maps_scene() {
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
        for (int k = 0; k < 4; ++k) checks.rgba8.push_back(c[k]);
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
SceneAsset cutouts_scene() {
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
            for (int k = 0; k < 4; ++k) holes.rgba8.push_back(texel[k]);
        }
    a.textures.push_back(holes);
    Texture stripes;   // 4 x 1, nearest: two opaque texels, two at alpha 80 / 255 ~ 0.31
    stripes.name = "pane stripes";
    stripes.width = 4;
    stripes.height = 1;
    stripes.nearest = true;
    for (int x = 0; x < 4; ++x) {
        const std::uint8_t texel[4] = {90, 140, 230, std::uint8_t(x < 2 ? 255 : 80)};
        for (int k = 0; k < 4; ++k) stripes.rgba8.push_back(texel[k]);
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

}  // namespace rt
