#include "ray_keys.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace rt {

namespace {

std::uint32_t shift_left(std::uint32_t x, unsigned s) { return s >= 32 ? 0u : x << s; }

// shaders/ray_sort.glsl: rs_interleave3.
std::uint32_t interleave3(glm::uvec3 c, glm::uvec3 bits) {
    std::uint32_t code = 0;
    for (unsigned level = std::max({bits.x, bits.y, bits.z}); level-- > 0;)
        for (int a = 0; a < 3; ++a)
            if (level < bits[a]) code = (code << 1) | ((c[a] >> level) & 1u);
    return code;
}

}  // namespace

const char* key_order_name(KeyOrder order) {
    return order == KeyOrder::direction_first ? "direction first" : "origin first";
}

namespace {

constexpr unsigned kMaxAxisBits = 24;       // a float resolves 2^24 cells; keeps 1u << bits defined
constexpr double kMinCell = 0x1p-100;       // the scale stays a normal float in [2^-100, 2^100] (ray_keys.h)
constexpr double kMaxExtent = 0x1p100;      // a larger (or non-finite) extent counts as flat: no bits

// Bits axis extent e needs with cubic cells of size c: the least b with e <= c 2^b (0 for e <= c).
unsigned axis_bits(double e, double c) {
    unsigned b = 0;
    while (b <= kMaxAxisBits && e > std::ldexp(c, int(b))) ++b;
    return b;   // kMaxAxisBits + 1: too many
}

float flush_subnormal(float x) { return std::fpclassify(x) == FP_SUBNORMAL ? 0.0f : x; }

}  // namespace

RayKeyLayout make_key_layout(glm::vec3 box_min, glm::vec3 box_max, unsigned key_bits, unsigned direction_bits,
                             unsigned lights, KeyOrder order) {
    if (key_bits < 1 || key_bits > 32)
        throw std::invalid_argument("--key-bits " + std::to_string(key_bits) + " is not in 1..32");
    if (direction_bits > key_bits)
        throw std::invalid_argument("--direction-bits " + std::to_string(direction_bits) + " exceeds --key-bits " +
                                    std::to_string(key_bits));
    RayKeyLayout layout;
    const unsigned origin_budget = key_bits - direction_bits;
    // Extents in double (a float box's extent is finite there even when it overflows a float).
    double extent[3];
    for (int a = 0; a < 3; ++a) {
        const double lo = box_min[a], hi = box_max[a];
        extent[a] = std::isfinite(lo) && std::isfinite(hi) && hi - lo > 0 && hi - lo <= kMaxExtent ? hi - lo : 0.0;
        layout.box_min[a] = std::isfinite(box_min[a]) ? flush_subnormal(box_min[a]) : 0.0f;
    }
    // The least cubic cell size whose bits fit the budget. The bit counts only change where c = extent_a / 2^k,
    // so the least such c is one of these.
    const double largest = std::max({extent[0], extent[1], extent[2]});
    double cell = 0.0;
    if (origin_budget > 0 && largest > 0) {
        cell = std::max(largest, kMinCell);   // 0 bits on every axis: always fits
        for (int a = 0; a < 3; ++a)
            for (unsigned k = 1; k <= kMaxAxisBits && extent[a] > 0; ++k) {
                const double c = std::max(std::ldexp(extent[a], -int(k)), kMinCell);
                if (c >= cell) continue;
                unsigned total = 0;
                bool fits = true;
                for (int b = 0; b < 3; ++b) {
                    const unsigned bits = axis_bits(extent[b], c);
                    fits = fits && bits <= kMaxAxisBits;
                    total += bits;
                }
                if (fits && total <= origin_budget) cell = c;
            }
        for (int a = 0; a < 3; ++a) layout.origin_bits[a] = axis_bits(extent[a], cell);
        layout.origin_total = layout.origin_bits.x + layout.origin_bits.y + layout.origin_bits.z;
    }
    if (layout.origin_total > 0) {
        layout.origin_scale = float(1.0 / cell);
        layout.cell_size = 1.0 / double(layout.origin_scale);
    }
    layout.direction_bits = {(direction_bits + 1) / 2, direction_bits / 2};
    layout.direction_total = direction_bits;
    layout.key_bits = layout.origin_total + layout.direction_total;
    layout.direction_major = order == KeyOrder::direction_first;
    // Groups: 0 primary, 1 reflection, 2 refraction, 3 transparency (the trace queue's kinds), 3 + light for shadow
    // rays (the shadow queue's). The two queues are sorted apart, so group 3 never holds both transparency rays and
    // shadow rays to light 0; at least 4 groups, so that transparency has its own even in a scene without lights.
    layout.group_count = std::max(4u, 3 + lights);
    const unsigned group_bits = unsigned(std::bit_width(layout.group_count - 1));
    layout.hash_bits = std::min(layout.key_bits, 32 - group_bits);
    layout.hash_drop = layout.key_bits - layout.hash_bits;
    layout.sort_bits = group_bits + layout.hash_bits;
    return layout;
}

std::uint32_t quantize_axis(float o, float box_min, float scale, unsigned bits) {
    if (bits == 0) return 0;
    const float f = (o - box_min) * scale;
    const std::uint32_t cells = 1u << bits;
    if (!(f >= 0.0f)) return 0;   // below the box, or NaN
    if (f >= float(cells)) return cells - 1;
    return std::uint32_t(f);
}

std::uint32_t octahedral_cell(float n, float s, unsigned bits) {
    std::uint32_t c = 0;
    for (int bit = int(bits) - 1; bit >= 0; --bit) {
        const std::uint32_t t = c | (1u << bit);
        const float threshold = std::ldexp(float(t), 1 - int(bits)) - 1.0f;   // exact: a dyadic number
        const float limit = threshold * s;
        if (n >= limit) c = t;
    }
    return c;
}

std::uint32_t ray_group(const gpu::WavefrontRay& ray, const RayKeyLayout& layout) {
    const std::uint32_t kind = ray.depth_kind >> 16;
    const std::uint32_t group = kind == 1 ? 3 + ray.light : (kind == 0 ? 0 : kind - 1);
    return std::min(group, layout.group_count - 1);
}

std::uint32_t origin_code(glm::vec3 origin, const RayKeyLayout& layout) {
    glm::uvec3 oc;
    for (int a = 0; a < 3; ++a)
        oc[a] = quantize_axis(origin[a], layout.box_min[a], layout.origin_scale, layout.origin_bits[a]);
    return interleave3(oc, layout.origin_bits);
}

std::uint32_t ray_key(const gpu::WavefrontRay& ray, const RayKeyLayout& layout) {
    // BEGIN EXERCISE 05.ray_key: the C++ twin of ray_sort.glsl's rs_ray_key (RayKeys.* grade this one, RaySorter.*
    // compare the two bit for bit): origin_code, the octahedral direction cells, the two codes in the layout's
    // order, the top hash bits, the group above them.
    const std::uint32_t oc = origin_code(ray.origin, layout);
    const glm::vec3 d = ray.direction;
    const float s = (std::abs(d.x) + std::abs(d.y)) + std::abs(d.z);
    float nu = d.x, nv = d.y;
    if (d.z < 0.0f) {   // the lower hemisphere folds over the diamond's edges
        nu = (s - std::abs(d.y)) * (d.x >= 0.0f ? 1.0f : -1.0f);
        nv = (s - std::abs(d.x)) * (d.y >= 0.0f ? 1.0f : -1.0f);
    }
    const glm::uvec3 dc{octahedral_cell(nu, s, layout.direction_bits.x), octahedral_cell(nv, s, layout.direction_bits.y),
                        0u};
    const std::uint32_t direction_code = interleave3(dc, {layout.direction_bits, 0u});
    const std::uint32_t hash = layout.direction_major ? shift_left(direction_code, layout.origin_total) | oc
                                                      : shift_left(oc, layout.direction_total) | direction_code;
    const std::uint32_t kept = layout.hash_drop >= 32 ? 0u : hash >> layout.hash_drop;
    return shift_left(ray_group(ray, layout), layout.hash_bits) | kept;
    // STUB: return shift_left(ray_group(ray, layout), layout.hash_bits);
    // END EXERCISE
}

RayChunks compress(const std::vector<std::uint32_t>& keys) {
    RayChunks chunks;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (i == 0 || keys[i] != keys[i - 1]) {
            chunks.keys.push_back(keys[i]);
            chunks.bases.push_back(std::uint32_t(i));
            chunks.sizes.push_back(0);
        }
        ++chunks.sizes.back();
    }
    return chunks;
}

RayChunks sort_chunks(const RayChunks& chunks) {
    std::vector<std::size_t> order(chunks.keys.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return chunks.keys[a] < chunks.keys[b]; });
    RayChunks sorted;
    for (std::size_t c : order) {
        sorted.keys.push_back(chunks.keys[c]);
        sorted.bases.push_back(chunks.bases[c]);
        sorted.sizes.push_back(chunks.sizes[c]);
    }
    return sorted;
}

std::vector<std::uint32_t> decompress(const RayChunks& sorted, std::uint32_t first) {
    std::vector<std::uint32_t> order;
    // BEGIN EXERCISE 05.decompression: the C++ twin of skeleton.comp: chunk by chunk in sorted order, the queue
    // indices of its rays (first + the chunk's base, counting up over its size).
    for (std::size_t c = 0; c < sorted.keys.size(); ++c)
        for (std::uint32_t k = 0; k < sorted.sizes[c]; ++k) order.push_back(first + sorted.bases[c] + k);
    // STUB: for (std::size_t c = 0; c < sorted.keys.size(); ++c)
    // STUB:     for (std::uint32_t k = 0; k < sorted.sizes[c]; ++k) order.push_back(first + std::uint32_t(order.size()));
    // END EXERCISE
    return order;
}

std::vector<std::uint32_t> sorted_order(const std::vector<std::uint32_t>& keys, std::uint32_t first) {
    return decompress(sort_chunks(compress(keys)), first);
}

}  // namespace rt
