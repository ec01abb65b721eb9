// Draws README.md's figure: a ray-space hierarchy over 64 rays in one plane (z = 0), as the CPU twin builds it
// (ray_hierarchy.h), written as an SVG. Rays leave a curved mirror (the bottom arc) like reflection rays, in the
// queue's order; the level-1 nodes (4 rays each) and level-2 nodes (16 rays) are drawn as their origin sphere (a
// circle) and their cone (two lines at +-spread from the axis, from the sphere's centre). A triangle (its bounding
// sphere in grey) is tested against the level-2 nodes: a red node rejects it for all 16 of its rays at once.
//     build/bin/rh_figure 04_ray_hierarchy/hierarchy.svg
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "04_ray_hierarchy/ray_hierarchy.h"

using namespace rt;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: rh_figure OUT.svg\n");
        return 2;
    }
    std::vector<RhRay> rays;
    for (int i = 0; i < 64; ++i) {
        const float a = -1.0f + 2.0f * float(i) / 63.0f;   // along the mirror
        const glm::vec3 o(3.0f * a, 0.6f * a * a, 0.0f);
        const glm::vec3 n = glm::normalize(glm::vec3(-0.4f * a, 1.0f, 0.0f));   // the normal of y = x^2 / 15
        const glm::vec3 in = glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f));
        rays.push_back({o, in - 2.0f * glm::dot(in, n) * n});   // the reflection of a parallel beam
    }
    const auto levels = rh_build(rays, 4);
    const glm::vec3 tri[3] = {{3.2f, 5.0f, 0.0f}, {4.6f, 5.6f, 0.0f}, {3.6f, 6.4f, 0.0f}};
    const glm::vec4 ts = rh_triangle_sphere(tri[0], tri[1], tri[2]);

    std::ofstream svg(argv[1]);
    const float scale = 50.0f, ox = 300.0f, oy = 420.0f;   // world (x, y) -> svg (ox + s x, oy - s y)
    auto X = [&](float x) { return ox + scale * x; };
    auto Y = [&](float y) { return oy - scale * y; };
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='600' height='460' font-family='sans-serif' "
           "font-size='12'>\n<rect width='600' height='460' fill='white'/>\n";
    for (const RhRay& r : rays)
        svg << "<line x1='" << X(r.origin.x) << "' y1='" << Y(r.origin.y) << "' x2='" << X(r.origin.x + 7 * r.direction.x)
            << "' y2='" << Y(r.origin.y + 7 * r.direction.y) << "' stroke='#9ab' stroke-width='0.6'/>\n";
    auto node = [&](const RhNode& n, const char* colour, float width) {
        const float c = std::cos(n.cone.w), s = std::sin(n.cone.w);
        const glm::vec2 a(n.cone.x, n.cone.y);
        svg << "<circle cx='" << X(n.sphere.x) << "' cy='" << Y(n.sphere.y) << "' r='" << scale * n.sphere.w
            << "' fill='none' stroke='" << colour << "' stroke-width='" << width << "'/>\n";
        for (float sign : {-1.0f, 1.0f}) {
            const glm::vec2 d(a.x * c - sign * a.y * s, sign * a.x * s + a.y * c);
            svg << "<line x1='" << X(n.sphere.x) << "' y1='" << Y(n.sphere.y) << "' x2='" << X(n.sphere.x + 8 * d.x)
                << "' y2='" << Y(n.sphere.y + 8 * d.y) << "' stroke='" << colour << "' stroke-width='" << width
                << "' stroke-dasharray='4 3'/>\n";
        }
    };
    for (const RhNode& n : levels[1]) node(n, "#4a4", 0.8f);
    for (const RhNode& n : levels[2]) node(n, rh_may_hit(n, ts) ? "#26c" : "#d22", 1.6f);
    svg << "<circle cx='" << X(ts.x) << "' cy='" << Y(ts.y) << "' r='" << scale * ts.w
        << "' fill='#ddd' stroke='#888'/>\n<polygon points='";
    for (const glm::vec3& v : tri) svg << X(v.x) << "," << Y(v.y) << " ";
    svg << "' fill='#fc3' stroke='#a80'/>\n"
        << "<text x='10' y='20'>64 rays (grey) off a curved mirror; level 1: 16 nodes of 4 rays (green);</text>\n"
        << "<text x='10' y='36'>level 2: 4 nodes of 16 rays, blue if they may reach the triangle's sphere, red if "
           "culled.</text>\n"
        << "<text x='10' y='52'>Each node: a circle holding the origins, dashed lines at +-spread around its "
           "axis.</text>\n</svg>\n";
    std::printf("wrote %s: %zu level-1 and %zu level-2 nodes\n", argv[1], levels[1].size(), levels[2].size());
    return svg ? 0 : 1;
}
