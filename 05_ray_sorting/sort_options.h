// Stage 05's command-line options: whether and how each batch of rays is sorted, and the bits of its key. The
// renderer reads the struct; add_sort_options declares it to the command line (CLI11).
#pragma once

namespace CLI { class App; }

namespace rt {

enum class SortMode {
    off,         // queue order: exactly stage 04
    on,          // every batch sorted
    automatic,   // every batch sorted, the sorted order kept only where it is tighter (order_choice.h) and, checked,
                 // saves more pairs than it costs (sort_pays)
};
const char* sort_mode_name(SortMode mode);   // "off", "on", "auto"

// What a sort costs, in the hierarchy's pair tests, per batch and per ray: the defaults are below the low ends of what
// llvmpipe measured (05's README, "What a sort costs"), so a sort is dropped only where it surely does not pay.
constexpr unsigned kSortBatchCost = 4096;
constexpr unsigned kSortRayCost = 1;

// The key of each batch kind (ray_keys.h): reflection and refraction rays [coarse direction | cubic origin], shadow
// rays [cubic origin | direction].
struct SortOptions {
    SortMode mode = SortMode::automatic;   // --sort auto|on|off
    bool sorts() const { return mode != SortMode::off; }
    unsigned key_bits = 30;              // --key-bits: origin + direction bits of a key
    unsigned direction_bits = 4;         // --direction-bits: the coarse direction cell of reflection/refraction keys
    unsigned shadow_direction_bits = 12; // --shadow-direction-bits: the direction cell below a shadow key's origin
    unsigned fine_direction_bits = 8;    // --fine-direction-bits: --sort auto's second reflection/refraction key
                                         // (0 or = direction_bits: none)
    unsigned probe_every = 8;            // --probe-every: with auto, every how many frames a batch is measured
                                         // again (between, it takes the order that won: sort_memory.h)
    // --sort-batch-cost, --sort-ray-cost: with auto, what a sort costs, in the hierarchy's pair tests, per batch and
    // per ray: a kept sort must save more pairs than that when checked (order_choice.h: sort_pays).
    unsigned batch_cost = kSortBatchCost;
    unsigned ray_cost = kSortRayCost;
};

// --sort, --key-bits, --direction-bits, --shadow-direction-bits, --fine-direction-bits, --probe-every,
// --sort-batch-cost and --sort-ray-cost, written into `options` when parsed; a direction width given above --key-bits
// is refused once the line is parsed.
void add_sort_options(CLI::App& app, SortOptions& options);

}  // namespace rt
