// Stage 03: a uniform grid rebuilt on the GPU every frame, walked with the 3D-DDA. Everything but the technique is in
// common/ (README.md: what to read, in order).
#include "common/app/driver.h"
#include "grid_renderer.h"

int main(int argc, char** argv) {
    rt::GridRenderer renderer;
    return rt::run_stage("03_uniform_grid", argc, argv, renderer);
}
