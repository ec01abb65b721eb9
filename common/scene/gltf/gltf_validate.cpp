#include "gltf_validate.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "gltf_common.h"

namespace rt::gltf_detail {

void check_json_depth(std::string_view json) {
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (in_string) {
            if (c == '\\') ++i;   // skip the escaped character (\" does not end the string)
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                invalid("JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

std::string_view glb_json_chunk(const std::vector<unsigned char>& glb) {
    auto u32 = [&](std::size_t at) {
        std::uint32_t v;
        std::memcpy(&v, glb.data() + at, 4);
        return v;
    };
    // 12-byte header (magic "glTF", version 2, total length), then chunk 0: length, type "JSON", data.
    if (glb.size() < 20 || std::memcmp(glb.data(), "glTF", 4) != 0) invalid("not a binary glTF file (bad header)");
    if (u32(4) != 2) invalid("binary glTF version " + std::to_string(u32(4)) + " (only 2 is supported)");
    const std::uint64_t length = u32(12);
    if (std::memcmp(glb.data() + 16, "JSON", 4) != 0) invalid("the first chunk of a binary glTF is not JSON");
    if (length > glb.size() - 20) invalid("the JSON chunk is longer than the file");
    return {reinterpret_cast<const char*>(glb.data() + 20), std::size_t(length)};
}

const std::vector<std::string>& supported_extensions() {
    static const std::vector<std::string> names = {
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior",
        "KHR_materials_specular", "KHR_materials_volume", "KHR_mesh_quantization", "KHR_texture_transform"};
    return names;
}

namespace {

using nlohmann::json;

bool is_index(const json& v) { return v.is_number_integer() && v.get<std::int64_t>() >= 0; }

// An array of exactly n numbers (glTF: translation 3, rotation 4, scale 3, matrix 16).
void check_numbers(const json& node, const char* key, std::size_t n, const std::string& where) {
    if (!node.contains(key)) return;
    const json& v = node.at(key);
    bool ok = v.is_array() && v.size() == n;
    for (std::size_t i = 0; ok && i < n; ++i) ok = v[i].is_number();
    if (!ok) invalid(where + ": " + key + " must be an array of " + std::to_string(n) + " numbers");
}

void check_index(const json& object, const char* key, const std::string& where) {
    if (object.contains(key) && !is_index(object.at(key)))
        invalid(where + ": " + key + " must be a non-negative integer (got " + std::string(object.at(key).type_name()) +
                ")");
}

void check_index_array(const json& object, const char* key, const std::string& where) {
    if (!object.contains(key)) return;
    const json& v = object.at(key);
    bool ok = v.is_array();
    for (std::size_t i = 0; ok && i < v.size(); ++i) ok = is_index(v[i]);
    if (!ok) invalid(where + ": " + key + " must be an array of non-negative integers");
}

const json& array_member(const json& root, const char* key) {
    static const json empty = json::array();
    if (!root.contains(key)) return empty;
    if (!root.at(key).is_array()) invalid(std::string(key) + " must be an array");
    return root.at(key);
}

void validate_asset(const json& root) {
    if (!root.contains("asset") || !root.at("asset").is_object()) invalid("no asset object");
    const json& asset = root.at("asset");
    if (!asset.contains("version") || !asset.at("version").is_string()) invalid("asset.version is missing");
    const std::string version = asset.at("version").get<std::string>();
    if (!version.starts_with("2.")) invalid("asset.version is '" + version + "'; only glTF 2.x is supported");
}

bool is_supported(const std::string& extension) {
    const auto& supported = supported_extensions();
    return std::find(supported.begin(), supported.end(), extension) != supported.end();
}

void validate_extensions(const json& root) {
    for (const json& name : array_member(root, "extensionsRequired")) {
        if (!name.is_string()) invalid("extensionsRequired must list names");
        const std::string n = name.get<std::string>();
        if (!is_supported(n)) invalid("requires extension " + n + ", which this loader does not support");
    }
}

// Every extension name the file uses: extensionsUsed, and the keys of each "extensions" object anywhere in it (a
// file may use one without listing it); "extras" hold an application's own data, not glTF, and are skipped. The JSON's
// depth is already bounded (check_json_depth), so recursion is safe.
void collect_extensions(const json& value, std::set<std::string>& names) {
    if (value.is_object()) {
        for (auto it = value.begin(); it != value.end(); ++it) {
            if (it.key() == "extras") continue;
            if (it.key() == "extensions" && it.value().is_object())
                for (auto e = it.value().begin(); e != it.value().end(); ++e) names.insert(e.key());
            collect_extensions(it.value(), names);
        }
    } else if (value.is_array()) {
        for (const json& v : value) collect_extensions(v, names);
    }
}

std::vector<std::string> unsupported_extensions_used(const json& root) {
    std::set<std::string> names;
    if (root.contains("extensionsUsed") && root.at("extensionsUsed").is_array())
        for (const json& name : root.at("extensionsUsed"))
            if (name.is_string()) names.insert(name.get<std::string>());
    collect_extensions(root, names);
    // Metadata (authorship, licences): nothing in them could change an image, so nothing is missing without them.
    static const std::set<std::string> metadata = {"KHR_xmp", "KHR_xmp_json_ld"};
    std::vector<std::string> out;
    for (const std::string& n : names)
        if (!is_supported(n) && !metadata.count(n)) out.push_back(n);
    return out;
}

void validate_nodes(const json& root) {
    const json& nodes = array_member(root, "nodes");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const json& node = nodes[i];
        const std::string where = "node " + std::to_string(i);
        if (!node.is_object()) invalid(where + " is not an object");
        check_index(node, "mesh", where);
        check_index(node, "camera", where);
        check_index(node, "skin", where);
        check_index_array(node, "children", where);
        check_numbers(node, "translation", 3, where);
        check_numbers(node, "rotation", 4, where);
        check_numbers(node, "scale", 3, where);
        check_numbers(node, "matrix", 16, where);
    }
}

void validate_scenes(const json& root) {
    const json& scenes = array_member(root, "scenes");
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        if (!scenes[i].is_object()) invalid("scene " + std::to_string(i) + " is not an object");
        check_index_array(scenes[i], "nodes", "scene " + std::to_string(i));
    }
    if (!root.contains("scene")) return;
    check_index(root, "scene", "the file");
    if (const std::uint64_t s = root.at("scene").get<std::uint64_t>(); s >= scenes.size())
        invalid("scene " + std::to_string(s) + " does not exist (the file has " + std::to_string(scenes.size()) +
                " scenes)");
}

}  // namespace

std::vector<std::string> validate_gltf_json(std::string_view text) {
    json root;
    try {
        root = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
        std::string what = e.what();   // says where; its "last read" part can be long: keep the start
        if (what.size() > 200) what = what.substr(0, 200) + "...";
        invalid("malformed JSON: " + what);
    }
    if (!root.is_object()) invalid("the JSON is not an object");
    try {
        validate_asset(root);
        validate_extensions(root);
        validate_scenes(root);
        validate_nodes(root);
        return unsupported_extensions_used(root);
    } catch (const json::exception& e) {   // the checks above test types first; this is a safety net
        invalid(e.what());
    }
}

}  // namespace rt::gltf_detail
