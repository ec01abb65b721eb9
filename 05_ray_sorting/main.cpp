// Stage 05: ray sorting (Garanzha & Loop 2010) under stage 04's ray-space hierarchy. Everything but the technique
// is in common/ and 04_ray_hierarchy/ (README.md: what to read, in order).
#include "common/app/driver.h"
#include "sorting_renderer.h"

int main(int argc, char** argv) {
    rt::RaySortingRenderer renderer;
    return rt::run_stage("05_ray_sorting", argc, argv, renderer);
}
