// bench_radix_sort: keys per second of RadixSort (32-bit keys with 32-bit values, all 32 bits sorted unless
// --key-bits says otherwise) for 2^16 .. 2^24 elements (--min-log, --max-log), with the GL renderer it ran on.
// docs/benchmarks.md keeps the results. Each size: one warm-up sort, then --repeats timed sorts (wall clock between
// glFinish calls). Stage 05 sorts arrays of a few thousand keys: --min-log 10 shows what a pass costs there.
//   build/bin/bench_radix_sort [--key-bits B] [--repeats R] [--min-log L] [--max-log L] [--backend auto|egl|osmesa]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "common/gpu/gl/context.h"
#include "radix_sort.h"

using namespace rt::gpu;

int main(int argc, char** argv) try {
    unsigned key_bits = 32, repeats = 3, min_log = 16, max_log = 24;
    std::string backend = "auto";
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string option = argv[i], value = argv[i + 1];
        if (option == "--key-bits") key_bits = unsigned(std::stoul(value));
        else if (option == "--repeats") repeats = unsigned(std::stoul(value));
        else if (option == "--min-log") min_log = unsigned(std::stoul(value));
        else if (option == "--max-log") max_log = unsigned(std::stoul(value));
        else if (option == "--backend") backend = value;
        else throw std::invalid_argument("unknown option " + option);
    }
    GpuContext context = create_headless_context(backend);
    std::printf("renderer: %s\nkey_bits: %u, values: 32-bit, repeats: %u\n", context.renderer().c_str(), key_bits,
                repeats);
    std::printf("%10s %12s %14s\n", "elements", "ms/sort", "Mkeys/s");
    RadixSort sort;
    std::mt19937 rng(1);
    for (unsigned log = min_log; log <= max_log; ++log) {
        const std::size_t n = std::size_t(1) << log;
        std::vector<std::uint32_t> keys(n), values(n);
        for (std::size_t i = 0; i < n; ++i) keys[i] = std::uint32_t(rng()), values[i] = std::uint32_t(i);
        Buffer key_buffer = Buffer::from(keys), value_buffer = Buffer::from(values);
        Buffer original = Buffer::from(keys);
        sort.sort(key_buffer, value_buffer, n, key_bits);   // warm-up (scratch buffers, shader caches)
        double seconds = 0.0;
        for (unsigned r = 0; r < repeats; ++r) {
            original.copy_to(key_buffer, n * 4);   // sort unsorted keys every time
            glFinish();
            const auto start = std::chrono::steady_clock::now();
            sort.sort(key_buffer, value_buffer, n, key_bits);
            glFinish();
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        const double per_sort = seconds / repeats;
        std::printf("%10zu %12.2f %14.1f\n", n, per_sort * 1e3, double(n) / per_sort * 1e-6);
        std::fflush(stdout);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_radix_sort: error: %s\n", e.what());
    return 2;
}
