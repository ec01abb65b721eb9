#include "hit_compare.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace rt {

namespace {

constexpr std::size_t kExamplesPerCategory = 5;

auto key(const HitRecord& r) { return std::make_tuple(r.sample, r.pixel, r.path, r.kind_light); }
auto sample_of(const HitRecord& r) { return std::make_pair(r.sample, r.pixel); }
std::uint32_t kind_of(const HitRecord& r) { return std::uint32_t(ray_kind(r.kind_light)); }

std::string describe(const HitRecord& r) {
    char text[160];
    const std::uint32_t kind = kind_of(r);
    std::snprintf(text, sizeof text, "sample %u pixel %u path %u %s%s", r.sample, r.pixel, r.path,
                  ray_kind_name(RayKind(kind)),
                  kind == std::uint32_t(RayKind::Shadow)
                      ? (" light " + std::to_string(light_index(r.kind_light)) + " cell " +
                         std::to_string(light_sample(r.kind_light))).c_str()
                      : "");
    return text;
}

std::string describe_hit(const HitRecord& r) {
    char text[64];
    std::snprintf(text, sizeof text, "triangle %d t %.9g", r.triangle, double(r.t));
    return text;
}

void sort_by_key(std::vector<HitRecord>& records, const char* which) {
    std::sort(records.begin(), records.end(), [](const HitRecord& x, const HitRecord& y) { return key(x) < key(y); });
    const auto duplicate = std::adjacent_find(records.begin(), records.end(),
                                              [](const HitRecord& x, const HitRecord& y) { return key(x) == key(y); });
    if (duplicate != records.end())
        throw std::invalid_argument(std::string("dump ") + which + " records the same ray twice: " + describe(*duplicate));
}

// Each component of b within `ulps` ulps of a's largest component (ulps of each component would make a coordinate
// near 0 differ by millions of ulps for an error of 1e-9 in a point at 10).
bool same_vector(const float* a, const float* b, std::uint32_t ulps) {
    const float scale = std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])});
    const double allowed = double(ulps) * double(std::nextafter(scale, INFINITY) - scale);
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(double(a[i]) - double(b[i])) <= allowed)) return false;
    return true;
}

bool same_ray(const HitRecord& a, const HitRecord& b, std::uint32_t ulps) {
    return same_vector(a.origin, b.origin, ulps) && same_vector(a.direction, b.direction, ulps);
}

enum class Outcome { Match, DifferentRay, DifferentTriangle, TBeyond };

Outcome compare_pair(const HitRecord& a, const HitRecord& b, const HitCompareOptions& options) {
    if (!same_ray(a, b, options.ray_ulps)) return Outcome::DifferentRay;
    if (a.triangle != b.triangle) return Outcome::DifferentTriangle;
    if (options.point_ulps ? !same_hit_point(a, a.t, b.t, *options.point_ulps) : ulp_distance(a.t, b.t) > options.t_ulps)
        return Outcome::TBeyond;
    return Outcome::Match;
}

// Walks two key-sorted lists together: visit(a, b) with nullptr for the side lacking the key.
template <class Visit>
void merge_by_key(const std::vector<HitRecord>& a, const std::vector<HitRecord>& b, Visit visit) {
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (j == b.size() || (i < a.size() && key(a[i]) < key(b[j]))) visit(&a[i++], nullptr);
        else if (i == a.size() || key(b[j]) < key(a[i])) visit(nullptr, &b[j++]);
        else visit(&a[i++], &b[j++]);
    }
}

}  // namespace

std::uint64_t ulp_distance(float a, float b) {
    if (std::isnan(a) || std::isnan(b))
        return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b) ? 0 : UINT64_MAX;
    // Map the float bits to integers that are ordered like the floats (-0 and +0 both to 0).
    auto ordered = [](float f) {
        const std::int64_t i = std::bit_cast<std::int32_t>(f);
        return i >= 0 ? i : std::int64_t(INT32_MIN) - i;
    };
    const std::int64_t d = ordered(a) - ordered(b);
    return std::uint64_t(d < 0 ? -d : d);
}

bool same_hit_point(const HitRecord& a, float ta, float tb, std::uint32_t ulps) {
    if (ulps == 0 || ta == tb) return std::bit_cast<std::uint32_t>(ta) == std::bit_cast<std::uint32_t>(tb);
    if (!std::isfinite(ta) || !std::isfinite(tb)) return false;
    double scale = 0.0, largest_step = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double o = a.origin[i], d = a.direction[i];
        scale = std::max({scale, std::fabs(o), std::fabs(o + double(ta) * d)});
        largest_step = std::max(largest_step, std::fabs(d));
    }
    // The points differ by |ta - tb| times the direction's largest component (computed in double: exact enough).
    const float s = float(scale);
    const double allowed = double(ulps) * double(std::nextafter(s, INFINITY) - s);
    return std::fabs(double(ta) - double(tb)) * largest_step <= allowed;
}

HitComparison compare_hits(std::vector<HitRecord> a, std::vector<HitRecord> b, const HitCompareOptions& options) {
    HitComparison c;
    c.empty = a.empty() || b.empty();
    sort_by_key(a, "A");
    sort_by_key(b, "B");
    for (const HitRecord& r : a) c.count_a[std::min(kind_of(r), std::uint32_t(kRayKinds - 1))]++;
    for (const HitRecord& r : b) c.count_b[std::min(kind_of(r), std::uint32_t(kRayKinds - 1))]++;
    c.primaries = c.count_a[0];

    std::array<std::size_t, 5> examples_of{};   // per category: only A, only B, ray, triangle, t
    auto example = [&](int category, const std::string& text) {
        if (examples_of[std::size_t(category)]++ < kExamplesPerCategory) c.examples.push_back(text);
    };

    // Pass 1: the primary rays. A differing one takes its whole tree out of pass 2.
    std::set<std::pair<std::uint32_t, std::uint32_t>> excluded_samples;
    merge_by_key(a, b, [&](const HitRecord* x, const HitRecord* y) {
        const HitRecord& r = x ? *x : *y;
        if (kind_of(r) != std::uint32_t(RayKind::Primary)) return;
        if (x && y && compare_pair(*x, *y, options) == Outcome::Match) return;
        c.differing_primaries++;
        excluded_samples.insert(sample_of(r));
        std::string text = "differing primary: " + describe(r);
        if (x) text += "  A: " + describe_hit(*x);
        if (y) text += "  B: " + describe_hit(*y);
        if (x && y && !same_ray(*x, *y, options.ray_ulps)) text += " (different ray)";
        example(0, text);
    });

    // Pass 2: every other ray.
    merge_by_key(a, b, [&](const HitRecord* x, const HitRecord* y) {
        const HitRecord& r = x ? *x : *y;
        if (kind_of(r) == std::uint32_t(RayKind::Primary)) return;
        if (excluded_samples.count(sample_of(r))) {
            c.excluded += (x ? 1 : 0) + (y ? 1 : 0);
            return;
        }
        c.compared++;
        if (!y) {
            c.only_a++;
            return example(1, "only in A: " + describe(r) + "  " + describe_hit(r));
        }
        if (!x) {
            c.only_b++;
            return example(1, "only in B: " + describe(r) + "  " + describe_hit(r));
        }
        switch (compare_pair(*x, *y, options)) {
            case Outcome::Match: break;
            case Outcome::DifferentRay: c.different_ray++; example(2, "different ray: " + describe(r)); break;
            case Outcome::DifferentTriangle:
                c.different_triangle++;
                example(3, "different triangle: " + describe(r) + "  A: " + describe_hit(*x) + "  B: " + describe_hit(*y));
                break;
            case Outcome::TBeyond:
                c.t_beyond++;
                example(4, (options.point_ulps ? "hit point beyond " + std::to_string(*options.point_ulps) + " ulps"
                                               : "t beyond " + std::to_string(options.t_ulps) + " ulps") +
                               " (t " + std::to_string(ulp_distance(x->t, y->t)) + " ulps apart): " + describe(r) +
                               "  A: " + describe_hit(*x) + "  B: " + describe_hit(*y));
                break;
        }
    });
    return c;
}

bool HitComparison::passed(const HitCompareOptions& options) const {
    if (empty) return false;
    return double(differing_primaries) <= options.primary_fraction * double(primaries) &&
           double(differences()) <= options.fraction * double(compared);
}

std::string HitComparison::report(const HitCompareOptions& options) const {
    std::string s;
    char line[256];
    s += "rays per kind (A / B):";
    for (int k = 0; k < kRayKinds; ++k) {
        std::snprintf(line, sizeof line, " %s %llu / %llu", ray_kind_name(RayKind(k)),
                      (unsigned long long)count_a[std::size_t(k)], (unsigned long long)count_b[std::size_t(k)]);
        s += line;
    }
    s += "\n";
    if (empty) s += "a dump has no rays: nothing was checked (did the stage record its hits?)\n";
    std::snprintf(line, sizeof line,
                  "differing primaries %llu of %llu (allowed %.4g%%), their trees excluded: %llu records\n",
                  (unsigned long long)differing_primaries, (unsigned long long)primaries,
                  100.0 * options.primary_fraction, (unsigned long long)excluded);
    s += line;
    std::snprintf(line, sizeof line,
                  "other rays compared %llu: only in A %llu, only in B %llu, different ray (> %u ulps) %llu, "
                  "different triangle %llu, %s beyond %u ulps %llu (allowed %.4g%%)\n",
                  (unsigned long long)compared, (unsigned long long)only_a, (unsigned long long)only_b,
                  options.ray_ulps, (unsigned long long)different_ray, (unsigned long long)different_triangle,
                  options.point_ulps ? "hit point" : "t", options.point_ulps.value_or(options.t_ulps),
                  (unsigned long long)t_beyond, 100.0 * options.fraction);
    s += line;
    for (const std::string& e : examples) s += "  " + e + "\n";
    s += passed(options) ? "PASS\n" : "FAIL\n";
    return s;
}

}  // namespace rt
