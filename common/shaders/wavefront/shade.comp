#version 450 core
// Shade pass: one thread per hit in wf_hits (docs/shading.md, "The colour of a hit"):
//   C = emissive + 0.03 kd + sum over lights of f E [unshadowed] + kr C(reflected) + kt C(refracted)
// Each term goes to the pixel weighted by the path's weight. The light terms wait for their shadow ray
// (ENABLE_SHADOWS): the shadow pass adds them when nothing blocks the light. kr C(reflected) and kt C(refracted)
// become rays of the next bounce (ENABLE_REFLECTIONS, ENABLE_REFRACTIONS), spawned while depth < max_depth and the
// child's weight is above the cut-off, as Whitted::radiance does. Code for an effect that is off is not compiled.
#include "wavefront.glsl"
#include "whitted.glsl"

layout(local_size_x = 64) in;

// Rays spawned by this thread, added to the counters once at the end.
uint shadow_rays = 0u, reflection_rays = 0u, refraction_rays = 0u;

void shade(WavefrontHit entry) {
    const WavefrontRay incoming = entry.ray;
    const Ray ray = wf_ray(incoming);
    Hit hit;
    hit.triangle = entry.triangle;
    hit.t = entry.t;
    hit.u = entry.u;
    hit.v = entry.v;
    const WhittedSurface w = whitted_surface(ray, hit);
    const SurfacePoint sp = w.point;
    const vec3 d = ray.direction;
    const vec3 n = sp.shading_normal;
    const vec3 weight = incoming.weight;

    // Local illumination.
    vec3 local = whitted_emission_ambient(w.coefficients);
    for (uint l = 0u; l < rt_light_count; ++l) {
        const Light light = rt_lights[l];
        vec3 to_light;
        float distance;
        const vec3 incidence = light_incidence(light, sp.position, n, to_light, distance);
        if (incidence == vec3(0.0)) continue;
        const vec3 c = shade_light(w.coefficients, incidence, n, to_light, -d);
#ifdef ENABLE_SHADOWS
        const vec3 origin = whitted_spawn_origin(sp, to_light, wf_offset, wf_epsilon);
        const float tmax = light.type == RT_LIGHT_DIRECTIONAL ? RT_INFINITY : rt_length(light.position - origin);
        wf_push_shadow_ray(wf_make_ray(origin, to_light, tmax, weight * c, incoming.pixel, wf_depth(incoming),
                                       WF_KIND_SHADOW));
        ++shadow_rays;
#else
        local += c;
#endif
    }
    wf_accumulate(incoming.pixel, weight * local);

#if defined(ENABLE_REFLECTIONS) || defined(ENABLE_REFRACTIONS)
    const uint depth = wf_depth(incoming);
    if (int(depth) >= wf_max_depth) return;
    float eta;
    const ReflectRefract k = whitted_coefficients(w, d, wf_fresnel, eta);
#ifdef ENABLE_REFLECTIONS
    const vec3 reflection_weight = weight * k.reflection;
    if (whitted_max_component(reflection_weight) > wf_cutoff) {
        const vec3 dir = whitted_reflection_dir(sp, d);
        wf_push_ray(wf_make_ray(whitted_spawn_origin(sp, dir, wf_offset, wf_epsilon), dir, RT_INFINITY,
                                reflection_weight, incoming.pixel, depth + 1u, WF_KIND_REFLECTION));
        ++reflection_rays;
    }
#endif
#ifdef ENABLE_REFRACTIONS
    const vec3 refraction_weight = weight * k.refraction;
    vec3 dir;
    if (whitted_max_component(refraction_weight) > wf_cutoff && whitted_refraction_dir(sp, d, eta, dir)) {
        wf_push_ray(wf_make_ray(whitted_spawn_origin(sp, dir, wf_offset, wf_epsilon), dir, RT_INFINITY,
                                refraction_weight, incoming.pixel, depth + 1u, WF_KIND_REFRACTION));
        ++refraction_rays;
    }
#endif
#endif
}

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    shade(wf_hits[i]);
    rt_counter_add(RT_COUNTER_SHADOW_RAYS, shadow_rays);
    rt_counter_add(RT_COUNTER_REFLECTION_RAYS, reflection_rays);
    rt_counter_add(RT_COUNTER_REFRACTION_RAYS, refraction_rays);
}
