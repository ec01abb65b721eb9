// Where a secondary ray starts: moving the hit point off its surface so the new ray does not hit that surface again
// ("self-intersection", seen as shadow acne or light leaking through thin walls). Selected with --offset.
//
//  epsilon  p + n * eps with a fixed eps (1e-4 scene units by default, --epsilon). Fails both ways: far from the
//           origin eps is below the spacing of floats (p + n*eps == p: acne), and for tiny or thin geometry it is
//           larger than the geometry (the ray starts behind a wall: light leaks).
//  robust   Waechter & Binder (2019), "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems
//           ch. 6: move p along n by a fixed number of units in the last place of each coordinate (integer
//           arithmetic on the float bits), and by a small absolute amount near the origin where ulps vanish. The
//           offset scales with the rounding error of p itself, at any magnitude.
//           Their constant is 256 ulps, sized for hit points computed as origin + t * direction, whose error grows
//           with t. Ours are interpolated from the triangle's vertices, P = w A + u B + v C, with an error of at most
//           gamma(7) |P| ~ 3.5 ulps per coordinate (Higham's bound; pbrt-v4 section 6.8.5) when the vertices are of
//           the size of P; 8 ulps covers that twice. 256 would push origins 0.25 units off the surface at 1e4 (a
//           float ulp there is ~1e-3), enough to shift shadows and refractions visibly (tests: FarScene.*).
//           Its limit: a triangle much larger than the coordinate it is offset in (vertices at +-1e4 around a point
//           at 0.1) has more interpolation error than ulps of P; the near-origin rule covers coordinates below 1/32.
//
// In both, n is the geometric normal turned to the side the new ray leaves on. GLSL twin:
// common/shaders/trace/offset.glsl.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "ray.h"

namespace rt {

enum class OffsetMethod : int { Epsilon = 0, Robust = 1 };

constexpr float kDefaultEpsilon = 1e-4f;

// Constants of Waechter & Binder for float (with int_scale 8 instead of their 256: see above); for double the same
// ulp count and an absolute step scaled to double's 29 extra mantissa bits.
template <class T> struct RobustOffsetConstants;
template <> struct RobustOffsetConstants<float> {
    static constexpr float origin = 1.0f / 32.0f;
    static constexpr float float_scale = 1.0f / 65536.0f;
    static constexpr float int_scale = 8.0f;
    using Int = std::int32_t;
};
template <> struct RobustOffsetConstants<double> {
    static constexpr double origin = 1.0 / 32.0;
    static constexpr double float_scale = 1.0 / 65536.0 / 536870912.0;
    static constexpr double int_scale = 8.0;
    using Int = std::int64_t;
};

// Offsets p along n (n points to the side the new ray leaves on; need not be unit length but should be close).
template <class T>
Vec3<T> offset_robust(const Vec3<T>& p, const Vec3<T>& n) {
    using K = RobustOffsetConstants<T>;
    using Int = typename K::Int;
    Vec3<T> result;
    for (int i = 0; i < 3; ++i) {
        const Int of = std::isfinite(n[i]) ? static_cast<Int>(K::int_scale * n[i]) : Int(0);
        const Int bits = std::bit_cast<Int>(p[i]);
        // Adding to the bit pattern moves away from zero for positive floats and towards zero for negative ones.
        const T moved = std::bit_cast<T>(static_cast<Int>(bits + (p[i] < T(0) ? -of : of)));
        result[i] = std::abs(p[i]) < K::origin ? p[i] + K::float_scale * n[i] : moved;
    }
    return result;
}

template <class T>
Vec3<T> offset_epsilon(const Vec3<T>& p, const Vec3<T>& n, T eps) {
    return p + n * eps;
}

// The knob. `geometric_normal` is the triangle's unit normal in any orientation; `direction` is the new ray's.
template <class T>
Vec3<T> offset_ray_origin(OffsetMethod method, const Vec3<T>& p, const Vec3<T>& geometric_normal,
                          const Vec3<T>& direction, T eps = T(kDefaultEpsilon)) {
    const Vec3<T> n = glm::dot(geometric_normal, direction) < T(0) ? -geometric_normal : geometric_normal;
    return method == OffsetMethod::Robust ? offset_robust(p, n) : offset_epsilon(p, n, eps);
}

}  // namespace rt
