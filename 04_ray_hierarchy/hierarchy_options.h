// Stage 04's command-line options: the shape of the ray hierarchy (branching, levels used), what its top nodes meet
// (the objects) and the cheap per-ray tests before the exact one. The traversal reads the struct;
// add_hierarchy_options declares it to the command line (CLI11).
#pragma once

#include <cstddef>

#include "object_tree.h"

namespace CLI { class App; }

namespace rt {

struct HierarchyOptions {
    int branching = 4;          // --branching: 4, 8 or 16 children per node
    int levels = 3;             // --levels: upper levels used (0 = up to a single root); 04's README: why 3
    ObjectMode objects = ObjectMode::tree;   // --objects: what the top ray nodes meet (object_tree.h)
    std::size_t pair_capacity = 0;   // tests: entries per pair buffer (0 = from the storage limit, at most 2^20)
    int hit_list_per_ray = 4;        // tests: hit-list entries per ray of a batch (fewer force prunes)
    bool speculate = true;           // tests: each batch first in one window per step, checked once after it
                                     // (gpu_ray_hierarchy.h); false: every window cut from read-back lengths
    bool sphere_test = true;         // --sphere-test: each ray against a triangle's sphere before the exact test
    bool box_test = true;            // --box-test: a ray or ray node against a triangle's or object node's box too
};

// --branching, --levels, --objects, --sphere-test and --box-test, written into `options` when parsed.
void add_hierarchy_options(CLI::App& app, HierarchyOptions& options);

}  // namespace rt
