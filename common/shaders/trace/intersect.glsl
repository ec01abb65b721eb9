// GLSL twins of common/trace/intersect.h (float), line by line. `precise` keeps every operation as written (no FMA
// contraction, no reordering), so with IEEE-exact arithmetic the results are bit-identical to the C++ ones.
// The watertight test redoes an edge function that rounds to exactly zero in double, as the C++ code does; define
// RT_NO_DOUBLE to compile that fallback out on hardware without fp64 (then edge-aimed rays may differ from the CPU).
#include "camera.glsl"

#define RT_INTERSECT_MOLLER 0
#define RT_INTERSECT_WATERTIGHT 1

struct Hit {
    float t, u, v;     // barycentrics of vertices 1 and 2: P = (1-u-v) A + u B + v C
    int triangle;      // -1 = miss
};

Hit no_hit() {
    Hit h;
    h.t = RT_INFINITY;
    h.u = 0.0;
    h.v = 0.0;
    h.triangle = -1;
    return h;
}

// Moller-Trumbore: true with t, u, v for a hit with 0 < t < tmax.
bool intersect_moller(Ray ray, vec3 a, vec3 b, vec3 c, out float t, out float u, out float v) {
    precise vec3 e1 = b - a;
    precise vec3 e2 = c - a;
    precise vec3 p = rt_cross(ray.direction, e2);
    precise float det = rt_dot(e1, p);
    t = 0.0;
    u = 0.0;
    v = 0.0;
    if (!(det != 0.0)) return false;             // parallel, degenerate, or NaN
    precise float inv_det = 1.0 / det;
    precise vec3 s = ray.origin - a;
    u = rt_dot(s, p) * inv_det;
    if (!(u >= 0.0 && u <= 1.0)) return false;
    precise vec3 q = rt_cross(s, e1);
    v = rt_dot(ray.direction, q) * inv_det;
    precise float uv = u + v;
    if (!(v >= 0.0 && uv <= 1.0)) return false;
    t = rt_dot(e2, q) * inv_det;
    return t > 0.0 && t < ray.tmax;
}

// Per-ray constants of the watertight test: dominant axis kz and the shear.
struct WatertightRay {
    int kx, ky, kz;
    float sx, sy, sz;
};

WatertightRay watertight_ray(vec3 d) {
    WatertightRay w;
    const vec3 ad = abs(d);
    w.kz = (ad.x > ad.y) ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    w.kx = (w.kz + 1) % 3;
    w.ky = (w.kx + 1) % 3;
    if (d[w.kz] < 0.0) {                         // keep the winding of the triangle
        const int k = w.kx;
        w.kx = w.ky;
        w.ky = k;
    }
    precise float sx = d[w.kx] / d[w.kz];
    precise float sy = d[w.ky] / d[w.kz];
    precise float sz = 1.0 / d[w.kz];
    w.sx = sx;
    w.sy = sy;
    w.sz = sz;
    return w;
}

bool intersect_watertight(Ray ray, WatertightRay w, vec3 a, vec3 b, vec3 c, out float t, out float u, out float v) {
    t = 0.0;
    u = 0.0;
    v = 0.0;
    precise vec3 A = a - ray.origin;
    precise vec3 B = b - ray.origin;
    precise vec3 C = c - ray.origin;
    precise float Ax = A[w.kx] - w.sx * A[w.kz], Ay = A[w.ky] - w.sy * A[w.kz];
    precise float Bx = B[w.kx] - w.sx * B[w.kz], By = B[w.ky] - w.sy * B[w.kz];
    precise float Cx = C[w.kx] - w.sx * C[w.kz], Cy = C[w.ky] - w.sy * C[w.kz];
    precise float U = Cx * By - Cy * Bx;
    precise float V = Ax * Cy - Ay * Cx;
    if ((U < 0.0 && V > 0.0) || (U > 0.0 && V < 0.0)) return false;   // early rejection (intersect.h)
    precise float W = Bx * Ay - By * Ax;
#ifndef RT_NO_DOUBLE
    if (U == 0.0 || V == 0.0 || W == 0.0) {
        precise double CxBy = double(Cx) * double(By), CyBx = double(Cy) * double(Bx);
        precise double AxCy = double(Ax) * double(Cy), AyCx = double(Ay) * double(Cx);
        precise double BxAy = double(Bx) * double(Ay), ByAx = double(By) * double(Ax);
        U = float(CxBy - CyBx);
        V = float(AxCy - AyCx);
        W = float(BxAy - ByAx);
    }
#endif
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    precise float det = U + V + W;
    if (!(det != 0.0)) return false;             // degenerate, edge-on, or NaN
    precise float Az = w.sz * A[w.kz], Bz = w.sz * B[w.kz], Cz = w.sz * C[w.kz];
    precise float T_scaled = U * Az + V * Bz + W * Cz;
    precise float tmax_det = ray.tmax * det;
    if (det < 0.0 ? (T_scaled >= 0.0 || T_scaled <= tmax_det) : (T_scaled <= 0.0 || T_scaled >= tmax_det))
        return false;
    precise float inv_det = 1.0 / det;
    u = V * inv_det;   // weight of b
    v = W * inv_det;   // weight of c
    t = T_scaled * inv_det;
    return rt_isfinite(t);
}

// The --intersect knob (the watertight per-ray setup recomputed; hot loops should call watertight_ray once per ray).
bool intersect_triangle(int method, Ray ray, vec3 a, vec3 b, vec3 c, out float t, out float u, out float v) {
    if (method == RT_INTERSECT_WATERTIGHT) return intersect_watertight(ray, watertight_ray(ray.direction), a, b, c, t, u, v);
    return intersect_moller(ray, a, b, c, t, u, v);
}
