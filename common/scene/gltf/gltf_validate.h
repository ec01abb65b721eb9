// Checks on a glTF file's JSON before tinygltf parses it (tinygltf recurses without a depth limit, and silently drops
// members of the wrong type). Internal to rt_scene; each check throws gltf_detail::Invalid with one line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rt::gltf_detail {

// Deepest nesting of JSON arrays and objects accepted. Real glTF files nest about 8 levels (extensions and extras
// add a few); 512 leaves room for deep extras while keeping every recursive JSON reader far from the stack's end.
constexpr int kMaxJsonDepth = 512;

// Refuses text whose arrays/objects nest deeper than kMaxJsonDepth. Scans the bytes (skipping strings), so it is
// safe on any input, valid JSON or not.
void check_json_depth(std::string_view json);

// The JSON chunk of a binary glTF (.glb) file (glTF 2.0, 4.4 "Binary glTF Layout"); header checks only.
std::string_view glb_json_chunk(const std::vector<unsigned char>& glb);

// The extensions the loader reads; a file may list only these in extensionsRequired.
const std::vector<std::string>& supported_extensions();

// Strict structure checks on the parsed JSON (the top-level JSON must already be depth-checked): asset.version 2.x,
// the scene index, extensionsRequired, and the JSON types and sizes of every node's members. Returns the extensions
// the file uses (extensionsUsed, or an "extensions" object anywhere) that the loader does not read, sorted by name.
std::vector<std::string> validate_gltf_json(std::string_view json);

}  // namespace rt::gltf_detail
