// The exact cross-stage check: two --dump-hits files matched ray by ray (hit_record.h), by the key
// (sample, pixel, path, kind, light), never by queue position.
//
// Every ray present in both is "the same ray" when each component of origin and of direction is within ray_ulps
// ulps of that vector's largest component; the same ray must then hit the same triangle (shadow rays: both occluded
// or both not) at t within t_ulps, or, with point_ulps, at hit points (origin + t direction) within point_ulps ulps
// of the largest coordinate of origin and hit point. The second is the bound an intersection can keep: it computes
// t from the vertices relative to the origin, so t's error follows the coordinates' size, not t's (a hit 0.007 from
// an origin at 0.27 differed by 55 ulps of t and 1 ulp of the point between an NVIDIA GPU and the CPU).
// A stage whose primary rays are rasterized (02) may hit another triangle than brute force on a shared edge: up to
// primary_fraction of the primary rays may differ, and every ray of such a pixel sample's tree is then excluded
// (its rays descend from another hit). Of the rays compared, at most `fraction` may differ in any way.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/trace/hit_record.h"

namespace rt {

struct HitCompareOptions {
    std::uint32_t ray_ulps = 0;
    std::uint32_t t_ulps = 0;
    std::optional<std::uint32_t> point_ulps;   // when set, t is compared at the hit point (above), not by t_ulps
    double primary_fraction = 0.0;
    double fraction = 0.0;
};

struct HitComparison {
    std::array<std::uint64_t, kRayKinds> count_a{}, count_b{};   // records per RayKind
    std::uint64_t primaries = 0;             // primary rays in A
    std::uint64_t differing_primaries = 0;   // primary rays that differ in any way (or are in one dump only)
    std::uint64_t excluded = 0;              // other records in the trees of differing primaries (A and B)
    std::uint64_t compared = 0;              // other records, counted once per key
    std::uint64_t only_a = 0, only_b = 0;
    std::uint64_t different_ray = 0;         // same key, origin or direction beyond ray_ulps
    std::uint64_t different_triangle = 0;    // same ray, another triangle (or occlusion answer)
    std::uint64_t t_beyond = 0;              // same ray and triangle, t beyond t_ulps (or the point beyond point_ulps)
    std::vector<std::string> examples;       // a few of each kind of difference, for the report
    bool empty = false;                      // a dump had no records: nothing was checked, which never passes

    std::uint64_t differences() const { return only_a + only_b + different_ray + different_triangle + t_beyond; }
    bool passed(const HitCompareOptions& options) const;
    std::string report(const HitCompareOptions& options) const;
};

// Distance in units in the last place between two floats (0 for equal values, +0 and -0 included); NaN is far from
// everything but a NaN with the same bits.
std::uint64_t ulp_distance(float a, float b);

// Whether two hits at ta and tb along the same ray (a's origin and direction) are within `ulps` ulps at the hit point,
// in units of the largest coordinate of the origin and the hit point (0: t bit for bit).
bool same_hit_point(const HitRecord& a, float ta, float tb, std::uint32_t ulps);

// Throws std::invalid_argument when a dump holds the same key twice.
HitComparison compare_hits(std::vector<HitRecord> a, std::vector<HitRecord> b, const HitCompareOptions& options);

}  // namespace rt
