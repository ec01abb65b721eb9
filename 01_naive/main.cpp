// Stage 01: Whitted ray tracing on the CPU, brute force. Everything but the technique is in common/.
#include "common/app/driver.h"
#include "naive_renderer.h"

int main(int argc, char** argv) {
    rt::NaiveRenderer renderer;
    return rt::run_stage("01_naive", argc, argv, renderer);
}
