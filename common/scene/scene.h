// The scene model shared by every stage.
//
// Two levels:
//  - SceneAsset: what a glTF file (or a built-in scene) describes: a node hierarchy with local transforms, meshes,
//    materials, textures, cameras, lights and animations. The glTF loader fills it, the exporter writes it, and the
//    built-in scenes are written directly in this form so that they export to glTF for free.
//  - Scene: one frame, flattened for rendering: every triangle in world space (three vertices each), the lights and
//    the camera in world space. Renderers only ever see a Scene; the CPU and GPU stages read the same arrays.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "common/scene/environment_map.h"

namespace rt {

// Thrown for anything that makes a scene unusable: missing file, malformed JSON, bad accessor, unsupported content,
// a scene beyond a limit. what() is one line meant for the user.
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// An axis-aligned box; empty until the first point is added.
struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    void add(const glm::vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    bool empty() const { return lo.x > hi.x; }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

// Largest irradiance a light delivers, emitted radiance and background radiance (docs/shading.md, "Limits"): far
// above any real scene (the sun gives 1e5 lux, a 1e7 cd lamp 1 mm away 1e13), low enough that summing lights,
// bounces and samples can never reach a float's 3.4e38. Clamped where the value is formed, so no pixel is infinite.
constexpr float kMaxRadiance = 1e20f;

// The working range of scene sizes (README, "Working range"): the ray/triangle tests multiply three coordinates
// (a determinant, a triple product), so a scene 1e-13 units across underflows a float's 1e-38 and one 1e13 across
// overflows its 3.4e38: geometry vanishes and the frame shows only the background (measured on builtin:whitted
// scaled: fine from 1e-13 to 1e13, all background at 1e-16 and 1e14). Scenes from kMinSceneExtent to
// kMaxSceneExtent across, with coordinates below kMaxSceneExtent, keep a margin of several orders on both sides.
constexpr double kMinSceneExtent = 1e-10, kMaxSceneExtent = 1e10;
// One line saying why a scene with these bounds is outside the working range, or "" when it is inside (or empty).
std::string working_range_problem(const Bounds& bounds);

// An 8-bit texture exactly as stored in the file: RGBA, sRGB-encoded for base colour. Sampling converts to linear.
// glTF sampler wrapS / wrapT (glTF 2.0, 3.8.4.3): what a texture coordinate outside [0, 1] reads.
enum class Wrap : int { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };

struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba8;   // width * height * 4 bytes, row 0 = top of the image (v = 0)
    bool nearest = false;              // glTF sampler magFilter NEAREST; else bilinear
    Wrap wrap_s = Wrap::Repeat;        // along u (the image's x)
    Wrap wrap_t = Wrap::Repeat;        // along v (the image's y)
};

// KHR_texture_transform: uv' = offset + R(rotation) S(scale) uv, glTF's T * R * S (the rotation turns uv
// counter-clockwise in the image, i.e. clockwise in uv with v down).
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;              // radians
    glm::vec2 scale{1.0f};
    bool is_identity() const { return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f); }
    bool operator==(const TextureTransform&) const = default;
};
// glTF alphaMode (docs/shading.md, "Alpha: cut-outs and blending"): OPAQUE ignores alpha; MASK cuts out where the
// opacity (base colour alpha times its texture's alpha) is below alpha_cutoff; BLEND is read as a cut-out at 0.5.
enum class AlphaMode : int { Opaque = 0, Mask = 1, Blend = 2 };

// glTF metallic-roughness material plus the extensions the course reads. Defaults are glTF's defaults.
// docs/shading.md maps these to Whitted's coefficients.
struct Material {
    std::string name;
    glm::vec4 base_color{1.0f};         // linear RGBA factor
    int base_color_texture = -1;        // index into textures, or -1
    float metallic = 1.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};           // emissiveFactor * KHR_materials_emissive_strength
    float transmission = 0.0f;          // KHR_materials_transmission
    float ior = 1.5f;                   // KHR_materials_ior
    float specular = 1.0f;              // KHR_materials_specular: specularFactor
    glm::vec3 specular_color{1.0f};     // KHR_materials_specular: specularColorFactor
    // Textures that scale the factors above, texel by texel (indices into textures, or -1):
    int metallic_roughness_texture = -1;   // linear: green scales roughness, blue scales metallic
    int emissive_texture = -1;             // sRGB: scales emissive
    int transmission_texture = -1;         // linear: red scales transmission (KHR_materials_transmission)
    // KHR_materials_volume (docs/shading.md, "Absorption"): Beer-Lambert inside a transmitting volume.
    glm::vec3 attenuation_color{1.0f};  // [0, 1]: the colour white light takes after attenuation_distance
    float attenuation_distance = std::numeric_limits<float>::infinity();   // > 0; infinite = no absorption
    float thickness = 0.0f;             // thicknessFactor; 0 = thin-walled (no volume, no absorption)
    // Normal map (docs/shading.md, "Normal maps"): a linear (not sRGB) tangent-space normal texture.
    int normal_texture = -1;            // index into textures, or -1
    float normal_scale = 1.0f;          // scales the map's x and y
    // KHR_texture_transform of the two textures (docs/shading.md, "Texture transform").
    TextureTransform base_color_transform;
    TextureTransform normal_transform;
    AlphaMode alpha_mode = AlphaMode::Opaque;   // glTF alphaMode
    float alpha_cutoff = 0.5f;                  // glTF alphaCutoff (MASK only)
    bool double_sided = false;                  // glTF doubleSided: an area light of it emits from both faces
};

enum class LightType : int { Point = 0, Spot = 1, Directional = 2 };

// KHR_lights_punctual. Intensity is candela for point/spot lights, lux for directional lights.
struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;                 // 0 = infinite
    float inner_cone = 0.0f;            // spot only, radians
    float outer_cone = 0.7853982f;      // spot only, radians (glTF default pi/4)
    // World space (filled by flatten; in a SceneAsset these are taken from the node the light hangs on).
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the way the light points (spot, directional)
};

// Which emissive surfaces light the scene (--area-lights; docs/shading.md, "Area lights"). Auto: those brighter than
// white (emitted radiance above kAreaLightMinRadiance in some channel, which glTF reaches only through
// KHR_materials_emissive_strength); all: every emitter; off: none (emission glows and lights nothing).
enum class AreaLightMode : int { Auto = 0, All = 1, Off = 2 };
constexpr float kAreaLightMinRadiance = 1.0f;

// An emissive surface that lights the scene: the triangles one mesh primitive of one node put in the frame, sampled
// as a grid of points (common/trace/area_light.h). A parallelogram (a quad: two triangles whose corners and texture
// coordinates form one) is sampled over corner + u edge_u + v edge_v; any other shape picks a triangle by area.
struct AreaLight {
    std::string name;                       // "node 'light', primitive 0"
    std::uint32_t first_triangle = 0;       // its triangles are [first_triangle, first_triangle + triangle_count)
    std::uint32_t triangle_count = 0;
    std::uint32_t material = 0;             // its emission: material.emissive x emissive texture at the point
    float area = 0.0f;                      // in world units squared
    bool two_sided = false;                 // the material is double-sided: both faces emit, else the front face
    bool parallelogram = false;
    glm::vec3 corner{0.0f}, edge_u{0.0f}, edge_v{0.0f};   // parallelogram: cross(edge_u, edge_v) is the front
    glm::vec2 uv_corner{0.0f}, uv_edge_u{0.0f}, uv_edge_v{0.0f};
    // Other shapes: Scene::area_light_cdf[cdf_first + k] is the share of the area in its triangles 0..k (the last 1).
    std::uint32_t cdf_first = 0;
};

// At most this many lights, punctual and area together: a shadow ray names its light in 16 bits (hit_record.h).
constexpr std::size_t kMaxLights = 65536;

enum class Projection : int { Perspective = 0, Orthographic = 1 };

// The ambient term of the local illumination: light no ray is traced for (docs/shading.md, "Ambient"). It costs no
// rays, so Whitted stays Whitted. Constant: a fixed fraction of the diffuse colour (the built-in scenes). Hemisphere:
// brighter from above than from below, weighted by the shading normal, so shape shows in shadow (glTF files).
enum class AmbientModel : int { None = 0, Constant = 1, Hemisphere = 2 };
const char* ambient_name(AmbientModel model);   // "none", "constant", "hemisphere"

struct Camera {
    std::string name;
    Projection projection = Projection::Perspective;
    float yfov = 0.6911f;               // radians (perspective)
    float aspect = 0.0f;                // 0 = take the image's aspect ratio
    float xmag = 1.0f, ymag = 1.0f;     // orthographic half extents
    float znear = 0.01f;
    float zfar = 0.0f;                  // 0 = infinite
    // World space (filled by flatten): eye position and an orthonormal frame. glTF cameras look down their local -Z
    // with +Y up, so forward = node's -Z, up = node's +Y, right = node's +X.
    glm::vec3 position{0.0f};
    glm::vec3 right{1.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
};

// ---------------------------------------------------------------------------------------------------------------
// SceneAsset: the glTF-shaped description.

struct Primitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;     // empty = computed (flat, per face) when flattened
    std::vector<glm::vec2> uvs;         // empty = no texture coordinates
    std::vector<glm::vec4> tangents;    // glTF TANGENT (xyz, w = handedness); empty = generated when needed
    std::vector<glm::vec4> colors;      // glTF COLOR_0 (linear RGBA, multiplies the base colour); empty = white
    std::vector<std::uint32_t> indices; // empty = non-indexed (every three positions form a triangle)
    int material = -1;                  // -1 = the glTF default material
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
};

struct Node {
    std::string name;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};   // w, x, y, z
    glm::vec3 scale{1.0f};
    std::optional<glm::mat4> matrix;              // when set, replaces T*R*S (glTF "matrix"; not animatable)
    int mesh = -1, camera = -1, light = -1;
    std::vector<int> children;
    glm::mat4 local_transform() const;
};

enum class AnimationPath : int { Translation, Rotation, Scale };
enum class Interpolation : int { Step, Linear, CubicSpline };

struct AnimationChannel {
    int node = -1;
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;
    // One value per key (xyz or quaternion xyzw in a vec4); CUBICSPLINE stores in-tangent, value, out-tangent per key.
    std::vector<glm::vec4> values;
};

struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels;
    float duration() const;
};

struct SceneAsset {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Node> nodes;
    std::vector<int> roots;             // the nodes of the displayed glTF scene
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Camera> cameras;        // projection parameters; placement comes from the node
    std::vector<Light> lights;          // colour/intensity/cone; placement comes from the node
    std::vector<Animation> animations;
    glm::vec3 background{0.0f};         // linear radiance of rays that leave the scene (at most kMaxRadiance)
    // Whether the scene says what rays leaving it see. Most glTF files do not (a glTF file has no background): then
    // the driver gives them the default world (docs/shading.md, "Defaults"), unless --background or --environment.
    bool has_world = true;
    AmbientModel ambient = AmbientModel::Constant;
    // Every file the loader read (the scene file, its buffers and images), as given; empty for built-in scenes.
    // The driver refuses an output path naming one of them.
    std::vector<std::string> input_files;
};

// ---------------------------------------------------------------------------------------------------------------
// Scene: one flattened frame.

struct Scene {
    std::string name;
    // Triangle soup in world space: triangle i uses entries 3i, 3i+1, 3i+2.
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;     // shading normals, unit length
    std::vector<glm::vec2> uvs;         // (0,0) where the mesh has none
    // Tangents (xyz unit, w = +-1 handedness), one per vertex like normals, only when a used material has a normal
    // map (docs/shading.md, "Normal maps"); empty otherwise.
    std::vector<glm::vec4> tangents;
    // Vertex colours (glTF COLOR_0, linear RGBA), one per vertex like normals, only when a mesh of the frame has them
    // (white for the vertices of those that do not); empty otherwise. They multiply the base colour and its alpha
    // (docs/shading.md, "Vertex colours").
    std::vector<glm::vec4> colors;
    std::vector<std::uint32_t> material_ids;   // one per triangle
    std::vector<Material> materials;    // never empty: a default material is appended when needed
    std::vector<Texture> textures;
    std::vector<Light> lights;
    // Emissive surfaces that light the scene (FlattenOptions::area_lights). In the lights' one numbering (shadow
    // rays, the stats) area light a is light lights.size() + a.
    std::vector<AreaLight> area_lights;
    std::vector<float> area_light_cdf;
    Camera camera;
    glm::vec3 background{0.0f};
    // --environment: what rays leaving the scene see instead of the background (environment.h); null = none.
    // Set by the driver after flatten, the same map for every frame.
    std::shared_ptr<const Environment> environment;
    Bounds bounds;
    // Documented defaults (docs/shading.md) applied because the asset had none; reported in the stats.
    bool default_camera = false;
    bool default_light = false;
    bool default_headlight = false;     // the default light is the headlight (the camera is the file's own)
    bool default_world = false;         // environment is the default world (set by the driver)
    AmbientModel ambient = AmbientModel::Constant;
    // The asset has animations: a later time is another frame (the viewer keeps rendering; a still one idles).
    bool animated = false;
    // Nonzero: this scene is handed, unchanged but for its camera, to frame after frame (the driver does so for a
    // still asset), so a GPU stage keeps it on the GPU and uploads it once (gpu_scene.h). 0: uploaded every frame.
    std::uint64_t still_id = 0;
    std::size_t triangle_count() const { return material_ids.size(); }
    std::size_t light_count() const { return lights.size() + area_lights.size(); }   // punctual and area
};

constexpr std::uint64_t kDefaultMaxTriangles = 20'000'000;

struct FlattenOptions {
    float time = 0.0f;            // seconds, for animations (all animations play together, clamped to their ends)
    int camera = -1;              // glTF camera index; -1 = first camera in node order, else auto-framed
    float aspect = 4.0f / 3.0f;   // image width / height, used for auto-framing
    bool add_default_light = true;   // when the asset has no light (an area light counts)
    AreaLightMode area_lights = AreaLightMode::Auto;
    // Refuse frames with more triangles than this (docs/shading.md, "Limits"): 20 million triangles are about 2 GB
    // of flattened vertex data before any acceleration structure or GPU copy.
    std::uint64_t max_triangles = kDefaultMaxTriangles;
};

// Whether a material is an area light under `mode`: emission above the mode's threshold, and opaque (a MASK or BLEND
// emitter glows but lights nothing: its light would pass through its holes).
bool material_is_area_light(const Material& m, AreaLightMode mode);

// Evaluates the asset at a time and bakes everything into world space. Triangles whose vertices are not finite are
// dropped (counted in dropped_triangles when given); degenerate triangles are kept (the intersectors must cope).
// Throws SceneError, before allocating, when the frame has more than options.max_triangles triangles.
Scene flatten(const SceneAsset& asset, const FlattenOptions& options, std::size_t* dropped_triangles = nullptr);

// The auto-framed camera and the lights used when an asset has none (docs/shading.md, "Defaults"): the key light
// with the auto-framed camera, the headlight with a camera of the file's own.
Camera default_camera(const Bounds& bounds, float aspect);
Light default_light(const Bounds& bounds);
Light default_headlight(const Bounds& bounds, const Camera& camera);
// Whether p lies strictly inside the bounds (not on a face).
bool strictly_inside(const Bounds& bounds, const glm::vec3& p);

}  // namespace rt
