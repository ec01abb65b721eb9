// Whitted's per-hit logic for the GPU stages: the body of Whitted::radiance (common/trace/whitted.h) cut into the
// pieces the wavefront passes need (common/shaders/wavefront/shade.comp). docs/shading.md is the contract; the
// arithmetic comes from the GLSL twins in shading.glsl, offset.glsl and scene.glsl, so a hit shades as on the CPU.
// Compile-time switches (rt::gpu::effect_defines): ENABLE_TEXTURES samples the material's textures,
// ENABLE_NORMAL_MAPS applies normal maps, ENABLE_ABSORPTION attenuates rays inside volumes (whitted_absorption).
#include "shading.glsl"
// (#include is resolved before the GLSL preprocessor runs, once per file, so these cannot sit under #ifdef; only the
// calls below are conditional, and uncalled functions leave nothing in the program.)
#include "texture_transform.glsl"
#include "normal_map.glsl"
#include "absorption.glsl"
#include "offset.glsl"
#include "intersect.glsl"

// What a hit needs for shading: the surface point (surface_point in whitted.h) and its Whitted coefficients.
struct WhittedSurface {
    SurfacePoint point;
    SurfaceCoefficients coefficients;
};

WhittedSurface whitted_surface(Ray ray, Hit hit) {
    WhittedSurface w;
    w.point = surface_point(ray, uint(hit.triangle), hit.u, hit.v);
    const Material material = rt_materials[w.point.material];
#ifdef ENABLE_NORMAL_MAPS
    if (material.normal_texture >= 0) {
        precise float bw = 1.0 - hit.u - hit.v;
        w.point.shading_normal = normal_mapped(uint(hit.triangle), bw, hit.u, hit.v, w.point.uv,
                                               w.point.geometric_normal, w.point.shading_normal, material);
    }
#endif
    SurfaceTexels texels = surface_texels(vec4(1.0));
#ifdef ENABLE_TEXTURES
    texels = sample_surface_textures(material, w.point.uv);
    texels.base *= w.point.color;   // COLOR_0 (white without RT_VERTEX_COLORS), as Whitted::radiance
#endif
    w.coefficients = surface_coefficients(material, texels);
    return w;
}

#ifdef ENABLE_ABSORPTION
// Whitted::radiance's `absorbed`: a hit on the back face of an absorbing volume ends a segment of length t inside
// it (docs/shading.md, "Absorption"); 1 otherwise.
vec3 whitted_absorption(WhittedSurface w, float t) {
    if (w.point.front_face) return vec3(1.0);
    return transmittance(rt_materials[w.point.material].attenuation, t);
}
#endif

// The part of the local illumination that needs no shadow ray: emission plus the ambient term (ambient_light, for
// the unit shading normal n).
vec3 whitted_emission_ambient(SurfaceCoefficients s, vec3 n) {
    precise vec3 c = s.emissive + ambient_light(s.diffuse, n);
    return c;
}

float whitted_max_component(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Where a secondary ray leaves the surface (--offset epsilon | robust), as Whitted::spawn_origin.
vec3 whitted_spawn_origin(SurfacePoint sp, vec3 direction, int offset_method, float epsilon) {
    return offset_ray_origin(offset_method, sp.position, sp.geometric_normal, direction, epsilon);
}

// Weights of the reflected and refracted rays for a ray arriving along d (Whitted::coefficients): the Fresnel term
// uses eta = n_incident / n_transmitted, 1/ior entering a front face, ior leaving through a back face.
ReflectRefract whitted_coefficients(WhittedSurface w, vec3 d, int fresnel_mode, out float eta) {
    // BEGIN EXERCISE 01.whitted_recursion: cos_i from the shading normal (clamped to [0, 1]), eta (1/ior entering a
    // front face, ior leaving), the Fresnel term, and reflect_refract_coefficients, as Whitted::radiance does.
    const float cos_i = rt_clamp(-rt_dot(d, w.point.shading_normal), 0.0, 1.0);
    precise float inv_ior = 1.0 / w.coefficients.ior;
    eta = w.point.front_face ? inv_ior : w.coefficients.ior;
    const float f = fresnel(fresnel_mode, cos_i, eta);
    return reflect_refract_coefficients(w.coefficients, w.point.front_face, cos_i, f);
    // STUB: eta = 1.0;
    // STUB: return ReflectRefract(vec3(0.0), vec3(0.0));
    // END EXERCISE
}

// Mirror direction about the shading normal; about the geometric normal when the shading normal would send the
// ray under the surface (strongly interpolated normals). Unit length.
vec3 whitted_reflection_dir(SurfacePoint sp, vec3 d) {
    // BEGIN EXERCISE 01.whitted_recursion: the mirror direction, with Whitted::radiance's fallback.
    vec3 dir = reflect_dir(d, sp.shading_normal);
    if (rt_dot(dir, sp.geometric_normal) <= 0.0) dir = reflect_dir(d, sp.geometric_normal);
    return rt_normalize(dir);
    // STUB: return d;
    // END EXERCISE
}

// Snell's law about the shading normal; false under total internal reflection. Unit length.
bool whitted_refraction_dir(SurfacePoint sp, vec3 d, float eta, out vec3 dir) {
    vec3 t;
    dir = vec3(0.0);
    if (!refract_dir(d, sp.shading_normal, eta, t)) return false;
    dir = rt_normalize(t);
    return true;
}
