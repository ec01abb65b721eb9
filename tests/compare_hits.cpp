// compare_hits A.hits B.hits: the exact cross-stage check of two --dump-hits files (see hit_compare.h for what is
// compared and the README for the bounds the tests use). Prints the counts and a few examples of each difference.
// Exit code: 0 pass, 1 fail, 2 bad input.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "common/app/hit_file.h"
#include "hit_compare.h"

int main(int argc, char** argv) {
    CLI::App app{"Compare two --dump-hits files ray by ray", "compare_hits"};
    std::string a_path, b_path;
    rt::HitCompareOptions options;
    app.add_option("a", a_path, "The stage's hits")->required();
    app.add_option("b", b_path, "The reference's hits")->required();
    app.add_option("--ray-ulps", options.ray_ulps, "Origin and direction components within this many ulps: the same ray")
        ->capture_default_str();
    app.add_option("--t-ulps", options.t_ulps, "Largest difference of t, in ulps, for the same ray and triangle")
        ->capture_default_str();
    app.add_option("--point-ulps", options.point_ulps,
                   "Compare t at the hit point instead: within this many ulps of the largest coordinate of origin "
                   "and hit point (hit_compare.h); replaces --t-ulps");
    app.add_option("--primary-fraction", options.primary_fraction,
                   "Fraction of primary rays that may differ (their pixel sample's tree is then excluded)")
        ->capture_default_str()->check(CLI::Range(0.0, 1.0));
    app.add_option("--fraction", options.fraction, "Fraction of the other rays that may differ in any way")
        ->capture_default_str()->check(CLI::Range(0.0, 1.0));
    CLI11_PARSE(app, argc, argv);
    try {
        const rt::HitComparison c = rt::compare_hits(rt::read_hit_file(a_path), rt::read_hit_file(b_path), options);
        std::printf("compare_hits %s %s\n%s", a_path.c_str(), b_path.c_str(), c.report(options).c_str());
        return c.passed(options) ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "compare_hits: error: %s\n", e.what());
        return 2;
    }
}
