// Standalone driver for the glTF fuzz target (no libFuzzer needed): exports every built-in scene with save_gltf (as
// .gltf and .glb), then for --seconds N feeds LLVMFuzzerTestOneInput structured mutations of them: deep JSON nesting,
// long node chains, massive instancing, extreme and non-finite numbers, members of the wrong JSON type, out-of-range
// indices, removed members, truncation and byte flips. Deterministic for a given --seed (and number of inputs run).
//
//   fuzz_gltf [--seconds N] [--seed S] [--save-failing DIR]
//
// Built with -fsanitize=address,undefined by scripts/test (build-sanitize); a finding aborts with the sanitizer's
// report. With --save-failing, each input is written to DIR/current.gltf|glb before it runs, so the one that
// crashed is left there.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/gltf/gltf_io.h"
#include "fuzz_gltf_target.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Bytes = std::vector<std::uint8_t>;

struct Seed {
    json doc;      // the .gltf JSON (buffers and images embedded as data URIs)
    Bytes glb;     // the same scene as .glb
};

Bytes read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

std::vector<Seed> export_builtin_scenes() {
    const fs::path dir = fs::temp_directory_path() / ("rt_fuzz_seeds_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir);
    std::vector<Seed> seeds;
    for (std::string name : rt::builtin_scene_names()) {
        if (name.starts_with("spheres")) name = "spheres:3";
        const rt::SceneAsset asset = rt::make_builtin_scene(name);
        rt::save_gltf(asset, (dir / "seed.gltf").string());
        rt::save_gltf(asset, (dir / "seed.glb").string());
        const Bytes text = read_bytes(dir / "seed.gltf");
        seeds.push_back({json::parse(text.begin(), text.end()), read_bytes(dir / "seed.glb")});
    }
    fs::remove_all(dir);
    return seeds;
}

// Every value in the document, as JSON pointers (the seeds are shallow, so recursion is fine here).
void collect(const json& v, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
    out.push_back(at);
    if (v.is_object())
        for (auto it = v.begin(); it != v.end(); ++it) collect(it.value(), at / it.key(), out);
    else if (v.is_array())
        for (std::size_t i = 0; i < v.size(); ++i) collect(v[i], at / i, out);
}

class Mutator {
  public:
    explicit Mutator(std::uint64_t seed) : rng_(seed) {}

    std::size_t below(std::size_t n) { return n == 0 ? 0 : std::size_t(rng_() % n); }
    bool chance(int percent) { return below(100) < std::size_t(percent); }

    // One structured change to the JSON document. A change that does not fit the document as earlier changes left it
    // (a member of the wrong type where it expects an array, say) is skipped.
    void mutate_json(json& doc) {
        try {
            mutate_json_once(doc);
        } catch (const json::exception&) {
        }
    }

    void mutate_json_once(json& doc) {
        std::vector<json::json_pointer> values;
        collect(doc, json::json_pointer(), values);
        const json::json_pointer at = values[below(values.size())];
        switch (below(9)) {
        case 0: {   // deep nesting somewhere (sometimes past the loader's limit)
            const std::size_t depth = chance(50) ? 400 + below(200) : 2000 + below(50'000);
            json nested = json::array();
            for (std::size_t i = 0; i < std::min<std::size_t>(depth, 700); ++i) nested = json::array({nested});
            if (depth > 700) deep_text_ = depth;   // deeper than a json value should hold: spliced into the text
            doc["extras"] = nested;
            break;
        }
        case 1: {   // a long chain of nodes ending in a mesh
            if (!doc.contains("meshes") || doc["meshes"].empty()) break;
            json& nodes = doc["nodes"];
            const std::size_t first = nodes.size(), length = 1 + below(chance(5) ? 20'000 : 200);
            for (std::size_t i = 0; i < length; ++i) {
                json node = {{"translation", {0.0, 0.01, 0.0}}};
                if (i + 1 < length) node["children"] = {first + i + 1};
                else node["mesh"] = 0;
                nodes.push_back(node);
            }
            doc["scenes"][0]["nodes"].push_back(first);
            break;
        }
        case 2: {   // massive instancing of one mesh
            if (!doc.contains("meshes") || doc["meshes"].empty()) break;
            const std::size_t first = doc["nodes"].size(), count = 1 + below(chance(10) ? 50'000 : 500);
            const std::size_t mesh = below(doc["meshes"].size());
            for (std::size_t i = 0; i < count; ++i) {
                doc["nodes"].push_back({{"mesh", mesh}});
                doc["scenes"][0]["nodes"].push_back(first + i);
            }
            break;
        }
        case 3: {   // an extreme number where a number was
            static const double extremes[] = {1e39, -1e39, 3.4e38, -3.4e38, 1e308, -1, -0.0, 0, 1e-45, 1e-320,
                                              4294967296.0, -2147483649.0, 65536, 0.5};
            if (doc[at].is_number()) doc[at] = extremes[below(std::size(extremes))];
            break;
        }
        case 4: {   // a value of the wrong JSON type
            static const json wrong[] = {"0", json::array(), json::object(), nullptr, true, json::array({1, 2}), -1};
            if (!at.empty()) doc[at] = wrong[below(std::size(wrong))];
            break;
        }
        case 5:   // an integer made out of range
            if (doc[at].is_number_integer()) doc[at] = chance(50) ? std::int64_t(below(1000)) : -std::int64_t(below(3));
            break;
        case 6:   // a member removed
            if (!at.empty()) doc[at.parent_pointer()].is_object() ? void(doc[at.parent_pointer()].erase(at.back()))
                                                                   : void(doc[at] = nullptr);
            break;
        case 7:   // a required extension (supported or not)
            doc["extensionsRequired"] = {chance(50) ? "KHR_materials_ior" : "EXT_unknown_extension"};
            break;
        case 8:   // a NaN or infinity, written as JSON cannot hold one
            if (doc[at].is_number()) nan_text_ = true;
            break;
        }
    }

    // Text-level changes: the splices mutate_json asked for, truncation and byte flips.
    void mutate_bytes(Bytes& bytes) {
        if (deep_text_ > 0) {
            std::string open(deep_text_, '['), close(deep_text_, ']');
            const std::string insert = R"("deep":)" + open + close + ",";
            splice_after_first_brace(bytes, insert);
            deep_text_ = 0;
        }
        if (nan_text_) {
            splice_after_first_brace(bytes, chance(50) ? R"("scene":NaN,)" : R"("x":[Infinity],)");
            nan_text_ = false;
        }
        if (chance(15) && !bytes.empty()) bytes.resize(below(bytes.size()));
        if (chance(25))
            for (std::size_t i = 0, n = 1 + below(8); i < n && !bytes.empty(); ++i)
                bytes[below(bytes.size())] ^= std::uint8_t(1u << below(8));
    }

    // A .glb whose JSON chunk is replaced by `doc` (and sometimes its binary chunk cut).
    Bytes rebuild_glb(const Bytes& glb, const json& doc) {
        std::string chunk = doc.dump();
        while (chunk.size() % 4) chunk += ' ';
        std::uint32_t json_length = 0;
        if (glb.size() >= 20) std::memcpy(&json_length, glb.data() + 12, 4);
        Bytes rest;
        if (glb.size() >= 20 && json_length <= glb.size() - 20) rest.assign(glb.begin() + 20 + json_length, glb.end());
        if (chance(10) && !rest.empty()) rest.resize(below(rest.size()));
        std::string out = "glTF";
        auto put32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        put32(2);
        put32(std::uint32_t(12 + 8 + chunk.size() + rest.size()));
        put32(std::uint32_t(chunk.size()));
        out += "JSON" + chunk;
        out.append(rest.begin(), rest.end());
        return Bytes(out.begin(), out.end());
    }

  private:
    static void splice_after_first_brace(Bytes& bytes, const std::string& text) {
        for (std::size_t i = 0; i < bytes.size(); ++i)
            if (bytes[i] == '{') {
                bytes.insert(bytes.begin() + std::ptrdiff_t(i + 1), text.begin(), text.end());
                return;
            }
    }

    std::mt19937_64 rng_;
    std::size_t deep_text_ = 0;
    bool nan_text_ = false;
};

}  // namespace

int main(int argc, char** argv) {
    double seconds = 10.0;
    std::uint64_t seed = 1;
    std::string save_dir;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--seconds") seconds = std::atof(argv[i + 1]);
        else if (flag == "--seed") seed = std::strtoull(argv[i + 1], nullptr, 10);
        else if (flag == "--save-failing") save_dir = argv[i + 1];
        else {
            std::fprintf(stderr, "fuzz_gltf: unknown option %s\n", flag.c_str());
            return 2;
        }
    }
    const std::vector<Seed> seeds = export_builtin_scenes();
    Mutator mutator(seed);
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    std::size_t runs = 0;
    while (elapsed() < seconds) {
        const Seed& s = seeds[mutator.below(seeds.size())];
        const bool binary = mutator.chance(30);
        json doc = s.doc;
        for (std::size_t i = 0, n = 1 + mutator.below(3); i < n; ++i) mutator.mutate_json(doc);
        Bytes input;
        if (binary) {
            input = mutator.chance(20) ? s.glb : mutator.rebuild_glb(s.glb, doc);
        } else {
            const std::string text = doc.dump();
            input.assign(text.begin(), text.end());
        }
        mutator.mutate_bytes(input);
        if (!save_dir.empty()) {
            std::ofstream out(fs::path(save_dir) / (binary ? "current.glb" : "current.gltf"), std::ios::binary);
            out.write(reinterpret_cast<const char*>(input.data()), std::streamsize(input.size()));
        }
        LLVMFuzzerTestOneInput(input.data(), input.size());
        ++runs;
    }
    std::printf("fuzz_gltf: %zu inputs (%zu loaded and flattened, the rest refused) from %zu built-in scenes in "
                "%.1f s (seed %llu), no findings\n",
                runs, fuzz_gltf_accepted_inputs(), seeds.size(), elapsed(), static_cast<unsigned long long>(seed));
    return 0;
}
