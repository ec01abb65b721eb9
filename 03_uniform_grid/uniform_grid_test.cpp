// The CPU uniform grid (uniform_grid.h): resolution heuristic, conservative triangle/cell test, build, and the 3D-DDA
// walk on its hard cases (dda_cases.h) against an exact reference walk; a grid traversal written with them gives
// brute force's closest hit exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/scene/builtin/builtin_scenes.h"
#include "dda_cases.h"
#include "uniform_grid.h"

namespace rt {
namespace {

Scene scene_named(const std::string& name, float time = 0.0f) {
    FlattenOptions options;
    options.time = time;
    return flatten(make_builtin_scene(name), options);
}

// ---------------------------------------------------------------------------------------------------------------
// Resolution and build.

TEST(GridResolution, CellsAreAboutLambdaTimesTrianglesShapedByTheBox) {
    Bounds b;
    b.add({0, 0, 0});
    b.add({4, 2, 1});
    const glm::ivec3 res = choose_resolution(b, 1000, 4.0f);
    const double cells = double(res.x) * res.y * res.z;
    EXPECT_GT(cells, 4000.0 * 0.7);
    EXPECT_LT(cells, 4000.0 * 2.0);   // ceil on each axis rounds up
    EXPECT_GT(res.x, res.y);
    EXPECT_GT(res.y, res.z);
}

TEST(GridResolution, FlatEmptyAndTinyScenes) {
    Bounds flat;
    flat.add({0, 0, 0});
    flat.add({10, 0, 10});
    EXPECT_EQ(choose_resolution(flat, 100, 4.0f).y, 1);
    EXPECT_EQ(choose_resolution(Bounds{}, 100, 4.0f), glm::ivec3(1));
    EXPECT_EQ(choose_resolution(flat, 0, 4.0f), glm::ivec3(1));
    Bounds huge;
    huge.add({0, 0, 0});
    huge.add({1, 1, 1});
    EXPECT_EQ(choose_resolution(huge, 1u << 30, 4.0f), glm::ivec3(kMaxGridResPerAxis));
}

TEST(TriangleBoxOverlap, TouchingCountsAndAGapDoesNot) {
    const glm::vec3 c(0.0f), h(1.0f);
    // A triangle lying in the box's face plane x = 1, and one just beyond it.
    EXPECT_TRUE(triangle_box_overlap(c, h, {1, -0.5f, -0.5f}, {1, 0.5f, -0.5f}, {1, 0, 0.5f}));
    EXPECT_FALSE(triangle_box_overlap(c, h, {1.01f, -0.5f, -0.5f}, {1.01f, 0.5f, -0.5f}, {1.01f, 0, 0.5f}));
    // Touching the box at a corner only.
    EXPECT_TRUE(triangle_box_overlap(c, h, {1, 1, 1}, {3, 1, 1}, {1, 3, 1}));
    // A large triangle cutting through the box with every vertex outside it.
    EXPECT_TRUE(triangle_box_overlap(c, h, {-10, -10, 0}, {10, -10, 0}, {0, 10, 0}));
    // Bounding boxes overlap, but the plane passes beside the corner (separated by the triangle's normal).
    EXPECT_FALSE(triangle_box_overlap(c, h, {1.5f, 3, 0}, {3, 1.5f, 0}, {3, 3, 3}));
    // An edge/edge separating axis: a thin sliver passing beside a box edge.
    EXPECT_FALSE(triangle_box_overlap(c, h, {2.2f, 0, -5}, {0, 2.2f, -5}, {0, 2.2f, 5}));
}

TEST(GridBuild, TriangleInACellBoundaryPlaneIsListedOnBothSides) {
    Scene s;
    s.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 1, -1}, {1, 1, -1}, {1, 1, 1}};   // the second spans z
    s.material_ids = {0, 0};
    s.bounds.add({0, 0, -1});
    s.bounds.add({2, 2, 1});
    const CpuGrid grid = build_grid(s, {2, 2, 2});
    // Triangle 0 lies in z = 0, the boundary between the z = 0 and z = 1 layers: all 4 cells of both layers.
    int listed = 0;
    for (const auto& cell : grid.cells) listed += std::count(cell.begin(), cell.end(), 0u);
    EXPECT_EQ(listed, 8);
}

TEST(GridBuild, ListsAreSortedAndEveryHitPointIsInACellListingItsTriangle) {
    for (const char* name : {"whitted", "cornell", "spheres:16", "far", "dynamic"}) {
        const Scene s = scene_named(name);
        const CpuGrid grid = build_grid(s, choose_resolution(s.bounds, s.triangle_count(), kDefaultGridLambda));
        for (const auto& cell : grid.cells) EXPECT_TRUE(std::is_sorted(cell.begin(), cell.end())) << name;
        EXPECT_GE(grid.pairs(), s.triangle_count()) << name;
        // Every vertex lies in a cell that lists its triangle.
        const GridParams& g = grid.params;
        for (std::uint32_t t = 0; t < s.triangle_count(); ++t)
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 p = s.positions[3 * t + k];
                glm::ivec3 c;
                for (int a = 0; a < 3; ++a)
                    c[a] = std::clamp(int(std::floor((p[a] - g.lo[a]) / g.cell[a])), 0, g.res[a] - 1);
                const auto& list = grid.at(c);
                ASSERT_TRUE(std::binary_search(list.begin(), list.end(), t)) << name << " triangle " << t;
            }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The DDA against an exact reference walk.

std::vector<GridStep> dda(const dda_cases::DdaCase& c, bool* bound = nullptr) {
    std::vector<GridStep> steps;
    walk_grid(c.grid, c.origin, c.direction, c.tmax, [&](const GridStep& s) { steps.push_back(s); return true; },
              bound);
    return steps;
}

// The cells the ray passes through for a positive length, in double: every boundary crossing splits the ray, and
// the middle of each piece lies in one cell (lo <= p < hi; the last cell keeps its far face).
std::vector<glm::ivec3> reference_walk(const dda_cases::DdaCase& c, double min_length) {
    const GridParams& g = c.grid;
    double t_enter = 0.0, t_exit = c.tmax;
    std::vector<double> ts;
    for (int a = 0; a < 3; ++a) {
        const double o = c.origin[a], d = c.direction[a];
        const double b0 = grid_boundary(g, a, 0), b1 = grid_boundary(g, a, g.res[a]);
        if (d == 0.0) {
            if (o < b0 || o > b1) return {};
            continue;
        }
        const double t0 = (b0 - o) / d, t1 = (b1 - o) / d;
        t_enter = std::max(t_enter, std::min(t0, t1));
        t_exit = std::min(t_exit, std::max(t0, t1));
        for (int n = 0; n <= g.res[a]; ++n) ts.push_back((double(grid_boundary(g, a, n)) - o) / d);
    }
    if (!(t_enter < t_exit)) return {};
    ts.push_back(t_enter);
    ts.push_back(t_exit);
    std::sort(ts.begin(), ts.end());
    std::vector<glm::ivec3> cells;
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
        const double t0 = std::max(ts[i], t_enter), t1 = std::min(ts[i + 1], t_exit);
        if (!(t1 - t0 > min_length)) continue;
        const double tm = 0.5 * (t0 + t1);
        glm::ivec3 cell;
        for (int a = 0; a < 3; ++a) {
            const double p = double(c.origin[a]) + tm * double(c.direction[a]);
            int k = 0;
            while (k + 1 < g.res[a] && p >= double(grid_boundary(g, a, k + 1))) ++k;
            cell[a] = k;
        }
        if (cells.empty() || cells.back() != cell) cells.push_back(cell);
    }
    return cells;
}

// Float rounding of t, from the coordinates' size: pieces shorter than this are not compared.
double t_tolerance(const dda_cases::DdaCase& c) {
    const float far = std::max({glm::length(c.origin), glm::length(c.grid.lo),
                                glm::length(c.grid.lo + glm::vec3(c.grid.res) * c.grid.cell)});
    float dmin = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a)
        if (c.direction[a] != 0.0f) dmin = std::min(dmin, std::abs(c.direction[a]));
    return 64.0 * std::ldexp(double(far) + 1.0, -24) / dmin;
}

class DdaHardCase : public ::testing::TestWithParam<dda_cases::DdaCase> {};

TEST_P(DdaHardCase, VisitsTheCellsOfTheExactWalkInOrder) {
    const dda_cases::DdaCase& c = GetParam();
    bool bound = true;
    const std::vector<GridStep> steps = dda(c, &bound);
    EXPECT_FALSE(bound) << "the loop bound was reached";
    const double tol = t_tolerance(c);
    std::vector<glm::ivec3> visited;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const GridStep& s = steps[i];
        for (int a = 0; a < 3; ++a) {
            ASSERT_GE(s.cell[a], 0);
            ASSERT_LT(s.cell[a], c.grid.res[a]);
        }
        EXPECT_LE(s.t0, s.t1);
        if (i > 0) {
            EXPECT_EQ(s.t0, steps[i - 1].t1) << "t-ranges are contiguous";
        }
        if (s.t1 - s.t0 > tol && (visited.empty() || visited.back() != s.cell)) visited.push_back(s.cell);
    }
    const std::vector<glm::ivec3> expected = reference_walk(c, tol);
    ASSERT_EQ(visited.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(visited[i], expected[i]) << "step " << i;
}

INSTANTIATE_TEST_SUITE_P(Cpu, DdaHardCase, ::testing::ValuesIn(dda_cases::cases()),
                         [](const auto& test_case) { return test_case.param.name; });

TEST(Dda, RandomRaysFollowTheExactWalkAndNeverReachTheBound) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        dda_cases::DdaCase c{"random", dda_cases::grid({1 + i % 7, 1 + i % 5, 1 + i % 11}, {-1.0f, 0.0f, 2.0f},
                                                      {0.3f, 0.7f, 0.2f}),
                             {4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng)}, {u(rng), u(rng), u(rng)}};
        if (i % 4 == 0) c.direction[i % 3] = i % 8 == 0 ? 0.0f : -0.0f;
        bool bound = true;
        const std::vector<GridStep> steps = dda(c, &bound);
        ASSERT_FALSE(bound);
        const double tol = t_tolerance(c);
        std::vector<glm::ivec3> visited;
        for (const GridStep& s : steps)
            if (s.t1 - s.t0 > tol && (visited.empty() || visited.back() != s.cell)) visited.push_back(s.cell);
        ASSERT_EQ(visited, reference_walk(c, tol)) << "ray " << i;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The grid's closest hit is brute force's, exactly (the rule grid.glsl follows). Brute force as stage 02 runs it
// (02_raster_hybrid/shaders/brute_force.glsl, the CPU BruteForceTracer's rule): every triangle in id order, each hit shrinking
// tmax for the next and kept only when strictly closer (the scaled test may let an equal t through), so at an equal t
// the lowest id stays.
Hit<float> brute_force_as_02(const Scene& s, Ray<float> ray) {
    Hit<float> hit;
    const WatertightRay<float> w(ray.direction);
    for (std::uint32_t t = 0; t < s.triangle_count(); ++t) {
        float th, u, v;
        const glm::vec3 &a = s.positions[3 * t], &b = s.positions[3 * t + 1], &c = s.positions[3 * t + 2];
        if (intersect_watertight(ray, w, a, b, c, th, u, v) && th < hit.t) {
            hit = {th, u, v, std::int32_t(t)};
            ray.tmax = th;
        }
    }
    return hit;
}

TEST(GridTraversal, ClosestHitEqualsBruteForceOnRaysAimedAtVerticesAndEdges) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const char* name : {"whitted", "cornell", "spheres:16", "far", "dynamic"}) {
        const Scene s = scene_named(name);
        for (float lambda : {0.5f, 4.0f, 30.0f}) {
            const CpuGrid grid = build_grid(s, choose_resolution(s.bounds, s.triangle_count(), lambda));
            int hits = 0;
            for (int i = 0; i < 400; ++i) {
                // From the camera towards a vertex, an edge midpoint or a random point of a random triangle.
                const std::uint32_t t = std::uint32_t(u(rng) * float(s.triangle_count())) % s.triangle_count();
                const glm::vec3 a = s.positions[3 * t], b = s.positions[3 * t + 1], c = s.positions[3 * t + 2];
                const glm::vec3 target = i % 3 == 0 ? a : i % 3 == 1 ? 0.5f * (a + b) : a + u(rng) * (b - a) * 0.5f +
                                                                                          u(rng) * (c - a) * 0.5f;
                Ray<float> ray;
                ray.origin = s.camera.position;
                ray.direction = glm::normalize(target - ray.origin);
                const Hit<float> expected = brute_force_as_02(s, ray);
                GridTraceCount count;
                const Hit<float> got = grid_closest_hit(grid, s.positions, ray, IntersectMethod::Watertight, &count);
                ASSERT_FALSE(count.bound_reached);
                ASSERT_EQ(got.triangle, expected.triangle) << name << " lambda " << lambda << " ray " << i;
                if (expected.valid()) {
                    ASSERT_EQ(got.t, expected.t);
                    ++hits;
                }
            }
            EXPECT_GT(hits, 200) << name;
        }
    }
}

TEST(GridTraversal, AnExactTieGoesToTheLowestIdWithoutTheNearTiePhase) {
    // Triangles 0 and 1 are the same triangle, listed twice: the ray hits both at exactly the same t.
    Scene s;
    s.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    s.material_ids = {0, 0};
    s.bounds.add({-1, -1, -1});
    s.bounds.add({1, 1, 1});
    const CpuGrid grid = build_grid(s, {1, 1, 1});
    Ray<float> ray;
    ray.origin = {0.1f, 0.2f, -3};
    ray.direction = {0, 0, 1};
    GridTraceCount count;
    const Hit<float> got = grid_closest_hit(grid, s.positions, ray, IntersectMethod::Watertight, &count);
    EXPECT_EQ(got.triangle, 0);
    EXPECT_EQ(got.t, brute_force_as_02(s, ray).t);
    EXPECT_EQ(brute_force_as_02(s, ray).triangle, 0);
    EXPECT_EQ(count.tests, 2u);   // the walk's 2 tests only: no retest in brute force's order
}

}  // namespace
}  // namespace rt
