// Ray/triangle intersection: two methods, selected with --intersect.
//
//  moller      Moller & Trumbore (1997), "Fast, minimum storage ray-triangle intersection", as the papers teach it.
//              Fast, but an edge shared by two triangles is tested twice with different rounding, so a ray aimed at
//              the edge (or a shared vertex) can miss both triangles.
//  watertight  Woop, Benthin & Wald (2013), "Watertight ray/triangle intersection", JCGT 2(1). The ray is sheared
//              so it runs along +Z; the 2D edge functions are then evaluated identically for both triangles sharing an
//              edge (and redone in double when one is exactly zero), so no ray slips between them.
//
// The GLSL twins are in common/shaders/trace/intersect.glsl; common/gpu/glsl_twins/glsl_twins_test.cpp keeps the two in
// agreement.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "ray.h"

namespace rt {

enum class IntersectMethod : int { Moller = 0, Watertight = 1 };

// Moller-Trumbore. Returns true and fills t,u,v for a hit with 0 < t < tmax. Degenerate (zero-area) triangles and
// rays parallel to the plane give det == 0 and are misses; NaN inputs fail every comparison and are misses too.
template <class T>
bool intersect_moller(const Ray<T>& ray, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, T& t, T& u, T& v) {
    const Vec3<T> e1 = b - a;
    const Vec3<T> e2 = c - a;
    const Vec3<T> p = glm::cross(ray.direction, e2);
    const T det = glm::dot(e1, p);
    if (!(det != T(0))) return false;             // parallel, degenerate, or NaN
    const T inv_det = T(1) / det;
    const Vec3<T> s = ray.origin - a;
    u = glm::dot(s, p) * inv_det;
    if (!(u >= T(0) && u <= T(1))) return false;
    const Vec3<T> q = glm::cross(s, e1);
    v = glm::dot(ray.direction, q) * inv_det;
    if (!(v >= T(0) && u + v <= T(1))) return false;
    t = glm::dot(e2, q) * inv_det;
    return t > T(0) && t < ray.tmax;
}

// Per-ray constants of the watertight test (section 3 of the paper): the dominant axis kz and the shear, also as
// three vectors so that the sheared coordinates are dot products (Ax = A[kx] - sx A[kz] = dot(A, shear_x)): the
// terms multiplied by 0 and 1 are exact, so the rounding is the same as the paper's, without indexing by kx, ky, kz.
template <class T>
struct WatertightRay {
    int kx = 0, ky = 1, kz = 2;
    T sx = 0, sy = 0, sz = 1;
    Vec3<T> shear_x{1, 0, 0}, shear_y{0, 1, 0}, scale_z{0, 0, 1};
    explicit WatertightRay(const Vec3<T>& d) {
        const Vec3<T> ad = glm::abs(d);
        kz = (ad.x > ad.y) ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
        kx = (kz + 1) % 3;
        ky = (kx + 1) % 3;
        if (d[kz] < T(0)) std::swap(kx, ky);      // keep the winding of the triangle
        sx = d[kx] / d[kz];
        sy = d[ky] / d[kz];
        sz = T(1) / d[kz];
        shear_x = Vec3<T>(0);
        shear_y = Vec3<T>(0);
        scale_z = Vec3<T>(0);
        shear_x[kx] = T(1);
        shear_x[kz] = -sx;
        shear_y[ky] = T(1);
        shear_y[kz] = -sy;
        scale_z[kz] = sz;
    }
};

template <class T>
bool intersect_watertight(const Ray<T>& ray, const WatertightRay<T>& w, const Vec3<T>& a, const Vec3<T>& b,
                          const Vec3<T>& c, T& t, T& u, T& v) {
    // Vertices relative to the origin, sheared so the ray becomes the +Z axis through (0,0).
    const Vec3<T> A = a - ray.origin, B = b - ray.origin, C = c - ray.origin;
    const T Ax = glm::dot(A, w.shear_x), Ay = glm::dot(A, w.shear_y);
    const T Bx = glm::dot(B, w.shear_x), By = glm::dot(B, w.shear_y);
    const T Cx = glm::dot(C, w.shear_x), Cy = glm::dot(C, w.shear_y);
    // Scaled barycentrics: 2D edge functions of the origin.
    T U = Cx * By - Cy * Bx;
    T V = Ax * Cy - Ay * Cx;
    // Early rejection, as Moller-Trumbore rejects after its first barycentric: two nonzero edge functions of
    // opposite signs put the ray outside, whatever the third. (Most tests in a scene miss, so this halves the cost.)
    if ((U < T(0) && V > T(0)) || (U > T(0) && V < T(0))) return false;
    T W = Bx * Ay - By * Ax;
    if constexpr (sizeof(T) < sizeof(double)) {
        // An edge function that rounds to exactly zero is recomputed in double (paper, section 4.3), so the sign
        // decision on a shared edge is the same for both triangles.
        if (U == T(0) || V == T(0) || W == T(0)) {
            U = T(double(Cx) * double(By) - double(Cy) * double(Bx));
            V = T(double(Ax) * double(Cy) - double(Ay) * double(Cx));
            W = T(double(Bx) * double(Ay) - double(By) * double(Ax));
        }
    }
    if ((U < T(0) || V < T(0) || W < T(0)) && (U > T(0) || V > T(0) || W > T(0))) return false;
    const T det = U + V + W;
    if (!(det != T(0))) return false;             // degenerate, edge-on, or NaN
    const T Az = glm::dot(A, w.scale_z), Bz = glm::dot(B, w.scale_z), Cz = glm::dot(C, w.scale_z);
    const T T_scaled = U * Az + V * Bz + W * Cz;
    // Compare t with 0 and tmax without dividing (signs depend on det).
    if (det < T(0) ? (T_scaled >= T(0) || T_scaled <= ray.tmax * det) : (T_scaled <= T(0) || T_scaled >= ray.tmax * det))
        return false;
    const T inv_det = T(1) / det;
    u = V * inv_det;   // weight of b
    v = W * inv_det;   // weight of c
    t = T_scaled * inv_det;
    return std::isfinite(t);
}

// One entry point for the --intersect knob (the watertight per-ray setup is recomputed here; hot loops should
// build WatertightRay once per ray, as the tracers do).
template <class T>
bool intersect_triangle(IntersectMethod method, const Ray<T>& ray, const Vec3<T>& a, const Vec3<T>& b,
                        const Vec3<T>& c, T& t, T& u, T& v) {
    if (method == IntersectMethod::Watertight) return intersect_watertight(ray, WatertightRay<T>(ray.direction), a, b, c, t, u, v);
    return intersect_moller(ray, a, b, c, t, u, v);
}

}  // namespace rt
