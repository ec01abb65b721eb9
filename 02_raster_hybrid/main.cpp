// Stage 02: rasterized primary visibility, GPU-traced secondary rays. Everything but the technique is in common/.
#include "common/app/driver.h"
#include "hybrid_renderer.h"

int main(int argc, char** argv) {
    rt::HybridRenderer renderer;
    return rt::run_stage("02_raster_hybrid", argc, argv, renderer);
}
