// Binding points shared by C++ and GLSL: the same numbers as common/gpu/gl/bindings.h (common/gpu/gl/bindings_test.cpp
// checks them, and the struct layouts, through GL program interface queries).
//   SSBO 0..7 scene + counters, 8..15 common primitives, 16..31 stages (RT_BINDING_STAGE_FIRST + i), 32 area lights.
//   UBO 0 scene block, 1.. stages. Texture unit 0 scene textures, 1.. stages.

#define RT_BINDING_POSITIONS 0
#define RT_BINDING_NORMALS 1
#define RT_BINDING_UVS 2
#define RT_BINDING_MATERIAL_IDS 3
#define RT_BINDING_MATERIALS 4
#define RT_BINDING_LIGHTS 5
#define RT_BINDING_TEXTURE_INFO 6
#define RT_BINDING_COUNTERS 7

#define RT_BINDING_SCAN_IN 8
#define RT_BINDING_SCAN_OUT 9
#define RT_BINDING_SCAN_SUMS 10
#define RT_BINDING_COMPACT_FLAGS 11
#define RT_BINDING_COMPACT_OFFSETS 12
#define RT_BINDING_COMPACT_VALUES 13
#define RT_BINDING_COMPACT_OUT 14
#define RT_BINDING_HARNESS 15
// The radix sort reuses points of the scan and compaction (bindings.h says why).
#define RT_BINDING_SORT_COUNTS RT_BINDING_SCAN_IN
#define RT_BINDING_SORT_KEYS_IN RT_BINDING_COMPACT_FLAGS
#define RT_BINDING_SORT_VALUES_IN RT_BINDING_COMPACT_OFFSETS
#define RT_BINDING_SORT_KEYS_OUT RT_BINDING_COMPACT_VALUES
#define RT_BINDING_SORT_VALUES_OUT RT_BINDING_COMPACT_OUT
#define RT_BINDING_SORT_COUNT RT_BINDING_SCAN_OUT

#define RT_BINDING_STAGE_FIRST 16
#define RT_BINDING_AREA_LIGHTS 32   // the scene's area lights (RT_AREA_LIGHTS only)

#define RT_UBO_SCENE 0
#define RT_UBO_STAGE_FIRST 1

#define RT_TEXTURE_UNIT_TEXTURES 0
#define RT_TEXTURE_UNIT_ENVIRONMENT 0
#define RT_TEXTURE_UNIT_STAGE_FIRST 1
