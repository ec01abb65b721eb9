#include "ray_tree.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <tuple>

namespace rt {
namespace {

int path_depth(std::uint32_t path) {
    int d = 0;
    while (path > 1) path >>= 1, ++d;
    return d;
}

// Pre-order of the binary path numbers (1; 2 and its subtree; 3 and its subtree): compare the two paths at the
// depth of the shallower one; an ancestor comes before its descendants.
bool path_before(std::uint32_t a, std::uint32_t b) {
    const int da = path_depth(a), db = path_depth(b);
    const std::uint32_t a_at = da > db ? a >> (da - db) : a, b_at = db > da ? b >> (db - da) : b;
    if (a_at != b_at) return a_at < b_at;
    return da < db;
}

// "1 test", "2 tests"; "1 grid cells" stays as the stage names its steps.
std::string count_of(std::uint64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

RayKind kind_of(const HitRecord& r) { return ray_kind(r.kind_light); }

}  // namespace

std::vector<RayTreeLine> ray_tree(const std::vector<HitRecord>& hits, const std::vector<RayWork>& work,
                                  std::uint32_t pixel) {
    using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;   // sample, path, kind_light
    std::map<Key, std::pair<std::uint64_t, std::uint64_t>> cost;
    for (const RayWork& w : work) {
        auto& c = cost[Key{w.sample, w.path, w.kind_light}];
        c.first += w.tests;
        c.second += w.steps;
    }
    std::vector<RayTreeLine> lines;
    for (const HitRecord& r : hits) {
        if (r.pixel != pixel) continue;
        RayTreeLine line;
        line.ray = r;
        if (auto it = cost.find(Key{r.sample, r.path, r.kind_light}); it != cost.end()) {
            line.tests = it->second.first;
            line.steps = it->second.second;
            cost.erase(it);
        }
        lines.push_back(line);
    }
    for (const auto& [key, c] : cost) {   // work no ray of the dump names
        RayTreeLine line;
        line.ray.sample = std::get<0>(key);
        line.ray.pixel = pixel;
        line.ray.path = std::get<1>(key);
        line.ray.kind_light = std::get<2>(key);
        line.ray.triangle = -2;
        line.tests = c.first;
        line.steps = c.second;
        lines.push_back(line);
    }
    for (RayTreeLine& l : lines) l.depth = path_depth(l.ray.path) + (kind_of(l.ray) == RayKind::Shadow ? 1 : 0);
    std::stable_sort(lines.begin(), lines.end(), [](const RayTreeLine& a, const RayTreeLine& b) {
        if (a.ray.sample != b.ray.sample) return a.ray.sample < b.ray.sample;
        if (a.ray.path != b.ray.path) return path_before(a.ray.path, b.ray.path);
        const bool a_shadow = kind_of(a.ray) == RayKind::Shadow;
        const bool b_shadow = kind_of(b.ray) == RayKind::Shadow;
        if (a_shadow != b_shadow) return !a_shadow;   // the ray first, then the shadow rays of its hit
        if (light_index(a.ray.kind_light) != light_index(b.ray.kind_light))
            return light_index(a.ray.kind_light) < light_index(b.ray.kind_light);
        return light_sample(a.ray.kind_light) < light_sample(b.ray.kind_light);
    });
    return lines;
}

std::string format_ray_tree(const std::vector<RayTreeLine>& lines, int x, int y, std::uint64_t heatmap_tests,
                            const std::string& steps_name, std::uint32_t punctual_lights, int light_grid) {
    std::uint64_t tests = 0, steps = 0;
    for (const RayTreeLine& l : lines) tests += l.tests, steps += l.steps;
    char buf[512];
    std::snprintf(buf, sizeof buf, "pixel (%d, %d): %zu rays, %llu ray/triangle tests (its heatmap value: %llu)", x, y,
                  lines.size(), static_cast<unsigned long long>(tests), static_cast<unsigned long long>(heatmap_tests));
    std::string out = buf;
    if (!steps_name.empty())
        out += ", " + std::to_string(steps) + " " + steps_name;
    out += "\n";
    std::uint32_t sample = ~0u;
    for (const RayTreeLine& l : lines) {
        if (l.ray.sample != sample) {
            sample = l.ray.sample;
            out += "  sample " + std::to_string(sample) + "\n";
        }
        const HitRecord& r = l.ray;
        const RayKind kind = kind_of(r);
        std::string name = ray_kind_name(kind);
        name += kind == RayKind::Shadow ? " to light " + std::to_string(light_index(r.kind_light))
                                        : " path " + std::to_string(r.path);
        if (kind == RayKind::Shadow && light_index(r.kind_light) >= punctual_lights && light_grid > 0) {
            const std::uint32_t cell = light_sample(r.kind_light), n = std::uint32_t(light_grid);
            name += " cell (" + std::to_string(cell % n) + ", " + std::to_string(cell / n) + ")";
        }
        std::string hit;
        if (r.triangle == -2)
            hit = "(no such ray in the stage's records)";
        else if (kind == RayKind::Shadow)
            hit = r.triangle == 1 ? "blocked" : "reaches the light";
        else if (r.triangle >= 0) {
            std::snprintf(buf, sizeof buf, "hits triangle %d at t = %.6g", r.triangle, double(r.t));
            hit = buf;
        } else {
            hit = "misses";
        }
        std::snprintf(buf, sizeof buf, "%*s%-22s from (%.4g, %.4g, %.4g) along (%.4f, %.4f, %.4f): %s; ",
                      4 + 2 * l.depth, "", name.c_str(), double(r.origin[0]), double(r.origin[1]),
                      double(r.origin[2]), double(r.direction[0]), double(r.direction[1]), double(r.direction[2]),
                      hit.c_str());
        out += buf + count_of(l.tests, "test", "tests");
        if (!steps_name.empty()) out += ", " + std::to_string(l.steps) + " " + steps_name;
        out += "\n";
    }
    return out;
}

nlohmann::json ray_tree_json(const std::vector<RayTreeLine>& lines, int x, int y, std::uint64_t heatmap_tests,
                             const std::string& steps_name) {
    std::uint64_t tests = 0, steps = 0;
    for (const RayTreeLine& l : lines) tests += l.tests, steps += l.steps;
    std::size_t unnamed = 0;
    for (const RayTreeLine& l : lines) unnamed += l.ray.triangle == -2;
    return {{"x", x},         {"y", y},         {"rays", lines.size()}, {"tests", tests},
            {"steps", steps}, {"steps_name", steps_name}, {"heatmap_tests", heatmap_tests},
            {"work_without_a_ray", unnamed}};
}

}  // namespace rt
