// Reading and writing glTF 2.0 (.gltf and .glb) through tinygltf.
#pragma once

#include <string>

#include "common/scene/scene.h"

namespace rt {

// Errors are thrown as SceneError (scene.h), one line naming the file.

// Loads the default scene of a glTF file (.gltf or .glb by extension). Reads: node hierarchy and TRS/matrix
// transforms, TRIANGLES primitives (indexed or not; other modes are skipped with a warning), POSITION, NORMAL,
// TEXCOORD_0, materials (baseColor factor/texture, metallic, roughness, emissive, KHR_materials_emissive_strength,
// KHR_materials_transmission, KHR_materials_ior, KHR_materials_specular), cameras, KHR_lights_punctual and
// animations (translation/rotation/scale channels). Warnings go to `warnings` when given.
// Hostile input is refused before it can do harm (docs/shading.md, "Values from files" and "Limits"): JSON nested
// deeper than 512 levels, malformed structure, unsupported extensionsRequired, numbers that do not fit a float, URIs
// naming anything but a regular file (never opened, so a FIFO cannot block), oversized images. The scene file and
// every buffer and image file read are listed in the result's input_files.
SceneAsset load_gltf(const std::string& path, std::string* warnings = nullptr);

// Writes an asset as glTF 2.0 (.gltf with embedded buffers and images, or .glb by extension), using the same
// extensions as the loader, so load_gltf(save_gltf(a)) reproduces a's triangles, materials, lights and cameras.
// Writes to a temporary file and renames it, so a failure leaves nothing half-written.
void save_gltf(const SceneAsset& asset, const std::string& path);
// The bytes save_gltf writes (the format from path's extension), for a caller that manages its own temporary.
std::string gltf_file_bytes(const SceneAsset& asset, const std::string& path);

}  // namespace rt
