#include "sort_stats.h"

namespace rt {

void to_json(nlohmann::json& out, const SortFrameStats& f) {
    static const char* const kBatchKind[2] = {"trace", "shadow"};
    const SortOptions& o = f.options;
    out = {{"sort", o.sorts()}, {"mode", sort_mode_name(o.mode)}};
    if (!o.sorts()) return;
    nlohmann::json key = {{"key_bits", o.key_bits},
                          {"direction_bits", o.direction_bits},
                          {"shadow_direction_bits", f.shadow_direction_bits},
                          {"fine_direction_bits", f.fine_direction_bits},
                          {"groups", f.layouts[0].group_count}};
    for (int k = 0; k < 3; ++k) {
        if (k == 2 && f.fine_direction_bits == 0) continue;
        const RayKeyLayout& L = f.layouts[std::size_t(k)];
        key[k == 2 ? "trace_fine" : kBatchKind[k]] = {
            {"order", key_order_name(L.direction_major ? KeyOrder::direction_first : KeyOrder::origin_first)},
            {"cell_size", L.cell_size},
            {"origin_bits", {L.origin_bits.x, L.origin_bits.y, L.origin_bits.z}},
            {"octahedral_bits", {L.direction_bits.x, L.direction_bits.y}},
            {"bits_used", L.key_bits},
            {"hash_bits_dropped", L.hash_drop},
            {"sort_bits", L.sort_bits}};
    }
    out["key"] = key;
    nlohmann::json batches = nlohmann::json::object();
    for (std::size_t k = 0; k < 2; ++k) {
        const SortBatchStats& s = f.batches[k];
        if (s.batches == 0 && s.skipped_batches == 0) continue;
        batches[kBatchKind[k]] = {{"batches", s.batches},
                                  {"rays", s.rays},
                                  {"chunks", s.chunks},
                                  {"rays_per_chunk", s.chunks ? double(s.rays) / double(s.chunks) : 0.0},
                                  {"sorted_batches", f.kept[k].batches},
                                  {"sorted_rays", f.kept[k].rays},
                                  {"fine_batches", f.kept[k].fine_batches},
                                  {"measured_batches", s.measured_batches},
                                  {"skipped_batches", s.skipped_batches},
                                  {"skipped_rays", s.skipped_rays},
                                  {"checked_batches", s.checked_batches},
                                  {"sorts_dropped", s.sorts_dropped},
                                  {"sort_ms", f.sort_ms[k]}};
    }
    out["batches"] = batches;
    if (o.mode == SortMode::automatic) {
        out["probe_every"] = o.probe_every;
        out["batch_cost"] = o.batch_cost;
        out["ray_cost"] = o.ray_cost;
    }
    out["gpu_cpu_syncs"] = f.gpu_cpu_syncs;
}

}  // namespace rt
