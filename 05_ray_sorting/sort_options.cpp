#include "sort_options.h"

#include <string>
#include <tuple>

#include <CLI/CLI.hpp>

#include "common/app/options.h"

namespace rt {

const char* sort_mode_name(SortMode mode) {
    switch (mode) {
        case SortMode::off: return "off";
        case SortMode::on: return "on";
        case SortMode::automatic: return "auto";
    }
    return "?";
}

void add_sort_options(CLI::App& app, SortOptions& options) {
    app.add_option_function<std::string>(
           "--sort",
           [&options](const std::string& s) {
               options.mode = s == "on" ? SortMode::on : s == "off" ? SortMode::off : SortMode::automatic;
           },
           "Sort each batch of rays before building the hierarchy: auto (default: keep the sorted order only where "
           "it makes the lowest nodes tighter and, checked, saves more pairs than it costs), on (always) or off "
           "(exactly stage 04)")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    app.add_option("--key-bits", options.key_bits,
                   "Bits of a ray's key for its origin cell (cubic cells over the scene box) and direction cell")
        ->capture_default_str()
        ->check(whole_number_in(1, 32));
    app.add_option("--direction-bits", options.direction_bits,
                   "Of the key bits, those of the coarse direction cell above the origin in reflection and "
                   "refraction rays' keys")
        ->capture_default_str()
        ->check(whole_number_in(0, 32));
    CLI::Option* shadow_bits =
        app.add_option("--shadow-direction-bits", options.shadow_direction_bits,
                       "Of the key bits, those of the direction cell below the origin in shadow rays' keys (the "
                       "default gives way to half of a --key-bits below it)")
            ->capture_default_str()
            ->check(whole_number_in(0, 32));
    CLI::Option* fine_bits =
        app.add_option("--fine-direction-bits", options.fine_direction_bits,
                       "With --sort auto, reflection and refraction batches are also sorted with this many bits of "
                       "a finer direction cell, and the tighter order is kept (0: one key; the default gives way to "
                       "none under a shorter --key-bits)")
            ->capture_default_str()
            ->check(whole_number_in(0, 32));
    app.add_option("--probe-every", options.probe_every,
                   "With --sort auto, each batch takes the order that won when it was last measured (the queue's: "
                   "no sort; a sorted one: its one sort) and is measured again every this many frames (1: every "
                   "batch measured every frame)")
        ->capture_default_str()
        ->check(whole_number_in(1, 10000));
    app.add_option("--sort-batch-cost", options.batch_cost,
                   "With --sort auto, what sorting a batch costs in the hierarchy's pair tests, besides its rays': a "
                   "sort the measure kept is kept after its check only if it saves more pairs than both (0 and 0: "
                   "any saving)")
        ->capture_default_str()
        ->check(whole_number_in(0, 100000000));
    app.add_option("--sort-ray-cost", options.ray_cost,
                   "With --sort auto, what sorting costs per ray of the batch, in the hierarchy's pair tests")
        ->capture_default_str()
        ->check(whole_number_in(0, 100000));
    app.parse_complete_callback([&options, shadow_bits, fine_bits] {
        for (auto [name, bits, given] : {std::tuple{"--direction-bits", options.direction_bits, true},
                                         {"--shadow-direction-bits", options.shadow_direction_bits,
                                          shadow_bits->count() > 0},
                                         {"--fine-direction-bits", options.fine_direction_bits,
                                          fine_bits->count() > 0}})
            if (bits > options.key_bits && given)
                throw CLI::ValidationError(name, std::to_string(bits) + " exceeds --key-bits " +
                                                     std::to_string(options.key_bits));
    });
}

}  // namespace rt
