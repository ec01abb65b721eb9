// Draws README.md's second figure: the object tree (object_tree.h) over 64 triangles in one plane (z = 0), as the CPU
// twin builds it, and which of its nodes one node of the ray hierarchy meets, written as an SVG. The triangles lie in
// four clumps; the leaves (clusters of 4 triangles, in Morton order) are the thin circles, level 2 (4 clusters) the
// thick ones, the root dashed. A node of 16 rays from the bottom left (its sphere and cone in blue) is tested against
// the root, and each surviving pair splits one side (rh_split_rays): the tree nodes it reaches are drawn solid, the
// ones it culls for all its rays at once red.
//     build/bin/ot_figure 04_ray_hierarchy/object_tree.svg
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <set>
#include <vector>

#include "04_ray_hierarchy/object_tree.h"
#include "04_ray_hierarchy/ray_hierarchy.h"

using namespace rt;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: ot_figure OUT.svg\n");
        return 2;
    }
    std::mt19937 g(4);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<glm::vec3> v;
    const glm::vec2 clumps[4] = {{-3.5f, 5.5f}, {2.5f, 6.0f}, {3.5f, 1.5f}, {-0.5f, 3.0f}};
    for (int t = 0; t < 64; ++t) {
        const glm::vec2 c = clumps[t % 4] + 1.3f * glm::vec2(u(g), u(g));
        for (int k = 0; k < 3; ++k) v.emplace_back(c.x + 0.35f * u(g), c.y + 0.35f * u(g), 0.0f);
    }
    std::vector<glm::vec4> spheres;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t t = 0; t < 64; ++t) {
        spheres.push_back(rh_triangle_sphere(v[3 * t], v[3 * t + 1], v[3 * t + 2]));
        for (int k = 0; k < 3; ++k) lo = glm::min(lo, v[3 * t + k]), hi = glm::max(hi, v[3 * t + k]);
    }
    const ObjectTree tree = build_object_tree(spheres, lo, hi);
    // 16 rays from a small patch at the bottom left, towards the upper right.
    std::vector<RhRay> rays;
    for (int i = 0; i < 16; ++i)
        rays.push_back({glm::vec3(-5.5f + 0.08f * float(i % 4), -0.5f + 0.08f * float(i / 4), 0.0f),
                        glm::normalize(glm::vec3(1.0f, 0.55f + 0.02f * float(i), 0.0f))});
    const auto levels = rh_build(rays, 4);
    const RhNode& beam = levels.back()[0];
    // The pairs (beam or its descendants, tree node) the traversal tests: reached or culled, per tree node.
    std::set<std::uint32_t> reached, culled;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack = {{std::uint32_t(levels.size() - 1), 0u}};
    std::vector<std::uint32_t> objects = {std::uint32_t(tree.nodes.size() - 1)};
    std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t>> pairs = {{{stack[0]}, objects[0]}};
    while (!pairs.empty()) {
        const auto [ray, o] = pairs.back();
        pairs.pop_back();
        const RhNode& n = levels[ray.first][ray.second];
        const ObjectNode& node = tree.nodes[o];
        if (!rh_may_hit(n, node.sphere)) {
            culled.insert(o);
            continue;
        }
        reached.insert(o);
        if (node.level == 1) continue;   // the figure stops at the leaves
        if (ray.first > 0 && rh_split_rays(n, node.sphere)) {
            for (std::uint32_t k = ray.second * 4; k < std::min<std::uint32_t>(ray.second * 4 + 4, std::uint32_t(levels[ray.first - 1].size())); ++k)
                pairs.push_back({{ray.first - 1, k}, o});
        } else {
            for (std::uint32_t k = 0; k < node.count; ++k) pairs.push_back({ray, node.first + k});
        }
    }

    std::ofstream svg(argv[1]);
    const float scale = 38.0f, ox = 310.0f, oy = 440.0f;
    auto X = [&](float x) { return ox + scale * x; };
    auto Y = [&](float y) { return oy - scale * y; };
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='600' height='500' font-family='sans-serif' "
           "font-size='12'>\n<rect width='600' height='500' fill='white'/>\n";
    for (std::size_t t = 0; t < 64; ++t) {
        svg << "<polygon points='";
        for (int k = 0; k < 3; ++k) svg << X(v[3 * t + k].x) << "," << Y(v[3 * t + k].y) << " ";
        svg << "' fill='#fc3' stroke='#a80' stroke-width='0.5'/>\n";
    }
    for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
        const ObjectNode& n = tree.nodes[i];
        const bool root = i + 1 == tree.nodes.size();
        const char* colour = culled.count(i) ? "#d22" : (reached.count(i) ? "#2a2" : "#bbb");
        svg << "<circle cx='" << X(n.sphere.x) << "' cy='" << Y(n.sphere.y) << "' r='" << scale * n.sphere.w
            << "' fill='none' stroke='" << colour << "' stroke-width='" << (n.level == 1 ? 0.8 : 1.8) << "'"
            << (root ? " stroke-dasharray='6 4'" : "") << "/>\n";
    }
    for (const RhRay& r : rays)
        svg << "<line x1='" << X(r.origin.x) << "' y1='" << Y(r.origin.y) << "' x2='" << X(r.origin.x + 12 * r.direction.x)
            << "' y2='" << Y(r.origin.y + 12 * r.direction.y) << "' stroke='#9ab' stroke-width='0.6'/>\n";
    const float c = std::cos(beam.cone.w), s = std::sin(beam.cone.w);
    for (float sign : {-1.0f, 1.0f}) {
        const glm::vec2 d(beam.cone.x * c - sign * beam.cone.y * s, sign * beam.cone.x * s + beam.cone.y * c);
        svg << "<line x1='" << X(beam.sphere.x) << "' y1='" << Y(beam.sphere.y) << "' x2='" << X(beam.sphere.x + 12 * d.x)
            << "' y2='" << Y(beam.sphere.y + 12 * d.y) << "' stroke='#26c' stroke-width='1.4' stroke-dasharray='4 3'/>\n";
    }
    svg << "<circle cx='" << X(beam.sphere.x) << "' cy='" << Y(beam.sphere.y) << "' r='" << scale * beam.sphere.w
        << "' fill='none' stroke='#26c' stroke-width='1.4'/>\n"
        << "<text x='10' y='20'>64 triangles; the object tree: leaves of 4 triangles (thin), level 2 (thick), root "
           "(dashed).</text>\n"
        << "<text x='10' y='36'>A node of 16 rays (blue) against the tree, split by rh_split_rays: nodes reached "
           "green,</text>\n"
        << "<text x='10' y='52'>culled for all its rays at once red, never tested grey.</text>\n</svg>\n";
    std::printf("wrote %s: %zu tree nodes, %zu reached, %zu culled\n", argv[1], tree.nodes.size(), reached.size(),
                culled.size());
    return svg ? 0 : 1;
}
