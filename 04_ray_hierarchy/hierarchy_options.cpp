#include "hierarchy_options.h"

#include <CLI/CLI.hpp>

#include "common/app/options.h"

namespace rt {

void add_hierarchy_options(CLI::App& app, HierarchyOptions& options) {
    app.add_option("--branching", options.branching, "Children per node of the ray hierarchy: 4, 8 or 16")
        ->capture_default_str()
        ->check(whole_number_of({4, 8, 16}));
    app.add_option("--levels", options.levels,
                   "Upper levels of the hierarchy used above the rays (0 = all, up to a single root; default 3: with the object "
                   "tree, the levels above add node tests and steps and cull nothing more)")
        ->capture_default_str()
        ->check(whole_number_in(0, 32));
    app.add_option_function<std::string>(
           "--objects",
           [&options](const std::string& s) {
               options.objects = s == "triangles" ? ObjectMode::triangles
                                           : s == "meshes"  ? ObjectMode::meshes
                                                            : ObjectMode::tree;
           },
           "What the top ray nodes meet: tree (default: a tree of bounding spheres over the triangles, rebuilt each "
           "frame), meshes (runs of one material, then their triangles: Reis) or triangles (every triangle: Roger et "
           "al. 2007)")
        ->check(CLI::IsMember({"tree", "meshes", "triangles"}));
    app.add_option_function<std::string>(
           "--sphere-test", [&options](const std::string& s) { options.sphere_test = s == "on"; },
           "Test each ray against a triangle's bounding sphere before the exact ray/triangle test: on (default) or "
           "off (as in the papers; with --box-test off too, every (ray, triangle) pair the hierarchy leaves gets the "
           "exact test)")
        ->check(CLI::IsMember({"on", "off"}));
    app.add_option_function<std::string>(
           "--box-test", [&options](const std::string& s) { options.box_test = s == "on"; },
           "After a sphere, test against the axis-aligned box too (a triangle's, or an object node's: tight where a "
           "sphere is loose, on long, thin or large triangles), a single ray and a ray node alike: on (default) or "
           "off")
        ->check(CLI::IsMember({"on", "off"}));
}

}  // namespace rt
