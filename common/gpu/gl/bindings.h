// Binding points shared by C++ and GLSL. The GLSL side is common/shaders/bindings.glsl (#defines with the same
// names in upper case, RT_BINDING_POSITIONS = kBindingPositions, ...). bindings_test.cpp compiles the GLSL
// declarations and checks, through GL's program interface queries, that every binding here and every std430/std140
// struct offset and array stride of gpu_scene.h and wavefront.h is what the shaders declare.
//
// SSBO bindings (GL_SHADER_STORAGE_BUFFER):
//   0..7    the scene, bound once by GpuScene::bind() (plus the counters)
//   8..15   the common GPU primitives (scan, compaction); they bind these themselves for each call, so they never
//           disturb the scene's bindings
//   32      the scene's area lights, when it has some (GpuScene::bind)
//   16..    the stages' own buffers (acceleration structures, ray queues, ...): kBindingStageFirst + i
//           (every implementation allows at least 96 SSBO binding points on NVIDIA and 32+ on Mesa, but a single
//           shader may use at most GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS of them, 16 on NVIDIA)
// UBO bindings: 0 = the scene block (camera, background, counts); stages from kUboStageFirst.
// Texture units: 0 = the --environment map when there is one (the scene's textures are in SSBO 6); stages from
// kTextureUnitStageFirst.
#pragma once

namespace rt::gpu {

// Scene (std430; layouts in common/shaders/trace/scene.glsl and gpu_scene.h).
constexpr unsigned kBindingPositions = 0;     // vec4[3 * triangles] (w unused)
constexpr unsigned kBindingNormals = 1;       // vec4[3 * triangles] (w unused)
constexpr unsigned kBindingUvs = 2;           // vec2[3 * triangles], then 2 a vertex of colours (COLOR_0)
constexpr unsigned kBindingMaterialIds = 3;   // uint[triangles]
constexpr unsigned kBindingMaterials = 4;     // Material[]
constexpr unsigned kBindingLights = 5;        // Light[]
constexpr unsigned kBindingTextureInfo = 6;   // sRGB tables, TextureInfo[], texels (scene.glsl: SceneTextures)
constexpr unsigned kBindingCounters = 7;      // uvec2[] 64-bit counters (counters.glsl, CounterBuffer)

// Common GPU primitives.
constexpr unsigned kBindingScanIn = 8;
constexpr unsigned kBindingScanOut = 9;
constexpr unsigned kBindingScanSums = 10;
constexpr unsigned kBindingCompactFlags = 11;
constexpr unsigned kBindingCompactOffsets = 12;
constexpr unsigned kBindingCompactValues = 13;
constexpr unsigned kBindingCompactOut = 14;
constexpr unsigned kBindingHarness = 15;      // the GLSL test harness' in/out buffer
// The radix sort (radix_sort.h) reuses points of the scan and compaction: each primitive rebinds its own per call.
constexpr unsigned kBindingSortCounts = kBindingScanIn;         // digit counts per tile, then their scan
constexpr unsigned kBindingSortKeysIn = kBindingCompactFlags;
constexpr unsigned kBindingSortValuesIn = kBindingCompactOffsets;
constexpr unsigned kBindingSortKeysOut = kBindingCompactValues;
constexpr unsigned kBindingSortValuesOut = kBindingCompactOut;
constexpr unsigned kBindingSortCount = kBindingScanOut;         // the element count, when only the GPU knows it

constexpr unsigned kBindingStageFirst = 16;
// The scene's area lights (GpuScene; scene.glsl, RT_AREA_LIGHTS), bound only for a scene that has them: after the
// stages' points (16..31) so no stage's binding moves; read by the shade pass alone (80 points on llvmpipe).
constexpr unsigned kBindingAreaLights = 32;

// The wavefront pipeline (wavefront.glsl: WF_BINDING_*), from kBindingStageFirst; a traversal's own buffers start at
// kBindingWavefrontTraversalFirst.
constexpr unsigned kBindingWavefrontRaysIn = kBindingStageFirst + 0;        // WavefrontRay[]: a pass' input queue
constexpr unsigned kBindingWavefrontHits = kBindingStageFirst + 1;          // WavefrontHit[]
constexpr unsigned kBindingWavefrontRaySlots = kBindingStageFirst + 2;      // WavefrontRay[]: a pass' output slots
constexpr unsigned kBindingWavefrontFlags = kBindingStageFirst + 3;         // uint[]: 1 = output slot used
constexpr unsigned kBindingWavefrontRadiance = kBindingStageFirst + 4;      // uint[9 per pixel]: 96-bit sums
constexpr unsigned kBindingWavefrontResults = kBindingStageFirst + 5;       // WavefrontTraceResult[] or uint[]
constexpr unsigned kBindingWavefrontImage = kBindingStageFirst + 6;         // vec4[] per pixel
constexpr unsigned kBindingWavefrontTestsPerPixel = kBindingStageFirst + 7; // uint[] per pixel (--heatmap)
constexpr unsigned kBindingWavefrontTraversalFirst = kBindingStageFirst + 8;

constexpr unsigned kUboScene = 0;
constexpr unsigned kUboStageFirst = 1;

constexpr unsigned kTextureUnitTextures = 0;
constexpr unsigned kTextureUnitEnvironment = 0;   // the --environment map (environment.glsl), only with RT_ENVIRONMENT
constexpr unsigned kTextureUnitStageFirst = 1;

}  // namespace rt::gpu
