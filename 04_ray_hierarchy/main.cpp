// Stage 04: the ray-space hierarchy of Roger, Assarsson & Holzschuch (2007). Everything but the technique is in
// common/ (README.md: what to read, in order).
#include "common/app/driver.h"
#include "ray_hierarchy_renderer.h"

int main(int argc, char** argv) {
    rt::RayHierarchyRenderer renderer;
    return rt::run_stage("04_ray_hierarchy", argc, argv, renderer);
}
