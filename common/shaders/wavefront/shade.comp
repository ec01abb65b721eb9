#version 450 core
// Shade pass: one thread per hit in wf_hits (docs/shading.md, "Local illumination"):
//   C = emissive + A(N) kd + sum over lights of f E [unshadowed] + kr C(reflected) + kt C(refracted)
// Each term goes to the pixel weighted by the path's weight. The light terms wait for their shadow ray
// (ENABLE_SHADOWS): the shadow pass adds them when nothing blocks the light. kr C(reflected) and kt C(refracted)
// become rays of the next bounce (ENABLE_REFLECTIONS, ENABLE_REFRACTIONS), spawned while depth < max_depth and the
// child's weight is above the cut-off, as Whitted::radiance does; on a BLEND surface read as coverage (ENABLE_BLEND)
// all of it is weighted by alpha and a transparency ray carries 1 - alpha on. Code for an effect that is off is not
// compiled.
//
// Outputs go to fixed slots of wf_ray_slots (flag 1 when used), so that compaction keeps them grouped and in the
// order of the hits: for hit i of n, its reflection ray at slot i, its refraction ray at n + i, its transparency ray
// (ENABLE_BLEND) at 2n + i, its shadow ray towards punctual light wf_light_first + l at wf_shadow_slot_base + l n + i
// (with area lights, each takes a block of n x cells slots, hit i's rays to its cells together). Each
// kind (and light) has its block, so the queues hold them in runs (rt::gpu::RayRun) whose lengths the host learns
// from the compaction. The secondary slots exist only with WF_SECONDARY_RAYS (some effect spawns rays and
// max_depth > 0); without it a BLEND surface still weights its terms by coverage. When the shadow slots of all
// lights would not fit in a storage block, rt::gpu::Wavefront runs the pass once per range of lights; only the last
// run (wf_shade_local = 1) adds the emission and ambient terms and spawns reflection, refraction and transparency
// rays.
#include "wavefront.glsl"
#include "common/shaders/trace/whitted.glsl"
// surface_opacity, for BLEND coverage (compiled only with ENABLE_CUTOUTS)
#include "common/shaders/trace/opacity.glsl"
// the area lights' samples (compiled only with RT_AREA_LIGHTS)
#include "common/shaders/trace/area_light.glsl"

layout(local_size_x = 64) in;

uniform uint wf_light_first;        // the lights whose shadow rays this run spawns
uniform uint wf_light_count;
uniform uint wf_shadow_slot_base;
uniform int wf_shade_local;
#ifdef RT_AREA_LIGHTS
// Lights from rt_light_count on are area lights, each wf_light_cells shadow slots per hit (the cells of its grid,
// --light-grid; hit i's at i * cells + cell of the light's block); wf_light_jitter: --light-jitter.
uniform uint wf_light_grid;
uniform uint wf_light_cells;
uniform int wf_light_jitter;
uniform uint wf_sample_index;   // the camera sample (--light-jitter's offsets depend on it)
#endif

// Rays spawned by this thread, added to the counters once at the end.
uint shadow_rays = 0u, reflection_rays = 0u, refraction_rays = 0u, transparency_rays = 0u, light_sample_rays = 0u;

// Shadow slots a light takes per hit before light l: one per punctual light, wf_light_cells per area light.
uint wf_light_slots_before(uint l) {
#ifdef RT_AREA_LIGHTS
    if (l > rt_light_count) return rt_light_count + (l - rt_light_count) * wf_light_cells;
#endif
    return l;
}

void shade(uint i, WavefrontHit entry) {
    const WavefrontRay incoming = entry.ray;
    const Ray ray = wf_ray(incoming);
    Hit hit;
    hit.triangle = entry.triangle;
    hit.t = entry.t;
    hit.u = entry.u;
    hit.v = entry.v;
    WhittedSurface w = whitted_surface(ray, hit);
    const SurfacePoint sp = w.point;
    const vec3 d = ray.direction;
    const vec3 n = sp.shading_normal;
    // BLEND as coverage (Whitted::radiance; docs/shading.md, "Alpha: cut-outs and blending"): the surface's own
    // terms and children take weight alpha, a transparency ray the rest; a BLEND surface does not refract.
    float coverage = 1.0;
#ifdef ENABLE_BLEND
    const bool blend_surface = rt_materials[sp.material].alpha_mode == RT_ALPHA_BLEND;
    if (blend_surface) {
        coverage = surface_opacity(uint(hit.triangle), hit.u, hit.v);
        w.coefficients.transmission = 0.0;   // its see-through part is the transparency ray
    }
#endif
#ifdef ENABLE_ABSORPTION
    // whitted_absorption: the segment this ray ran inside a volume
    const vec3 weight = incoming.weight * coverage * whitted_absorption(w, hit.t);
#else
    const vec3 weight = incoming.weight * coverage;
#endif

    const uint n_hits = wf_input_count;

    // Local illumination: the punctual lights, then each cell of each area light as a point light (Whitted::shade).
    vec3 local = whitted_emission_ambient(w.coefficients, n);
    const uint slots_first = wf_light_slots_before(wf_light_first);
    for (uint l = wf_light_first; l < wf_light_first + wf_light_count; ++l) {
#ifdef RT_AREA_LIGHTS
        if (l >= rt_light_count) {
            const AreaLight area = rt_area_light(l - rt_light_count);
            const vec2 offset = light_grid_offset(wf_light_jitter != 0, incoming.pixel, wf_sample_index, l);
            for (uint cell = 0u; cell < wf_light_cells; ++cell) {
#ifdef ENABLE_SHADOWS
                const uint slot = wf_shadow_slot_base + (wf_light_slots_before(l) - slots_first) * n_hits +
                                  i * wf_light_cells + cell;
                wf_flags[slot] = 0u;
#endif
                const AreaSample on_light = sample_area_light(area, light_grid_point(wf_light_grid, cell, offset));
                Light point;
                if (!area_sample_as_point_light(area, on_light, area_light_emission(area, on_light), wf_light_cells,
                                                sp.position, point))
                    continue;
                vec3 to_light;
                float distance;
                const vec3 incidence = light_incidence(point, sp.position, n, to_light, distance);
                if (incidence == vec3(0.0)) continue;
                const vec3 c = shade_light(w.coefficients, incidence, n, to_light, -d);
#ifdef ENABLE_SHADOWS
                const vec3 origin = whitted_spawn_origin(sp, to_light, wf_offset, wf_epsilon);
                const float tmax = area_shadow_tmax(wf_offset, wf_epsilon, on_light, origin, to_light);
                WavefrontRay shadow = wf_make_ray(origin, to_light, tmax, weight * c, incoming.pixel,
                                                  wf_depth(incoming), WF_KIND_SHADOW, incoming.path, l);
                shadow.light_sample = cell;
                wf_ray_slots[slot] = shadow;
                wf_flags[slot] = 1u;
                ++shadow_rays;
                ++light_sample_rays;
#else
                local += c;
#endif
            }
            continue;
        }
#endif
        const Light light = rt_lights[l];
        vec3 to_light;
        float distance;
        const vec3 incidence = light_incidence(light, sp.position, n, to_light, distance);
#ifdef ENABLE_SHADOWS
        const uint slot = wf_shadow_slot_base + (wf_light_slots_before(l) - slots_first) * n_hits + i;
        wf_flags[slot] = 0u;
#endif
        if (incidence == vec3(0.0)) continue;
        const vec3 c = shade_light(w.coefficients, incidence, n, to_light, -d);
#ifdef ENABLE_SHADOWS
        const vec3 origin = whitted_spawn_origin(sp, to_light, wf_offset, wf_epsilon);
        const float tmax = light.type == RT_LIGHT_DIRECTIONAL ? RT_INFINITY : rt_length(light.position - origin);
        wf_ray_slots[slot] = wf_make_ray(origin, to_light, tmax, weight * c, incoming.pixel, wf_depth(incoming),
                                         WF_KIND_SHADOW, incoming.path, l);
        wf_flags[slot] = 1u;
        ++shadow_rays;
#else
        local += c;
#endif
    }
    if (wf_shade_local == 0) return;
    wf_accumulate(incoming.pixel, weight * local);

#ifdef WF_SECONDARY_RAYS
    wf_flags[i] = 0u;
    wf_flags[n_hits + i] = 0u;
#ifdef ENABLE_BLEND
    wf_flags[2u * n_hits + i] = 0u;
#endif
    const uint depth = wf_depth(incoming);
    if (int(depth) >= wf_max_depth) return;
#ifdef ENABLE_BLEND
    // The transparency ray: straight on through the surface (path 2p + 1, as a refraction ray: a BLEND surface does
    // not refract), in its own block.
    const vec3 through_weight = incoming.weight * (1.0 - coverage);
    if (blend_surface && whitted_max_component(through_weight) > wf_cutoff) {
        wf_ray_slots[2u * n_hits + i] = wf_make_ray(whitted_spawn_origin(sp, d, wf_offset, wf_epsilon), d,
                                                    RT_INFINITY, through_weight, incoming.pixel, depth + 1u,
                                                    WF_KIND_TRANSPARENCY, 2u * incoming.path + 1u, 0u);
        wf_flags[2u * n_hits + i] = 1u;
        ++transparency_rays;
    }
#endif
    // BEGIN EXERCISE 01.whitted_recursion: the GLSL twin of Whitted::radiance's secondary rays, as a wavefront pass:
    // with k = whitted_coefficients(...), write a reflection ray (whitted_reflection_dir) to wf_ray_slots[i] and a
    // refraction ray (whitted_refraction_dir; none at total internal reflection) to wf_ray_slots[n_hits + i], each
    // only when its weight stays above wf_cutoff, starting at whitted_spawn_origin, with depth + 1 and path
    // 2 * path (+ 1 for refraction); set its wf_flags slot to 1 and count it (reflection_rays, refraction_rays).
    float eta;
    const ReflectRefract k = whitted_coefficients(w, d, wf_fresnel, eta);
#ifdef ENABLE_REFLECTIONS
    const vec3 reflection_weight = weight * k.reflection;
    if (whitted_max_component(reflection_weight) > wf_cutoff) {
        const vec3 dir = whitted_reflection_dir(sp, d);
        wf_ray_slots[i] = wf_make_ray(whitted_spawn_origin(sp, dir, wf_offset, wf_epsilon), dir, RT_INFINITY,
                                      reflection_weight, incoming.pixel, depth + 1u, WF_KIND_REFLECTION,
                                      2u * incoming.path, 0u);
        wf_flags[i] = 1u;
        ++reflection_rays;
    }
#endif
#ifdef ENABLE_REFRACTIONS
    const vec3 refraction_weight = weight * k.refraction;
    vec3 dir;
    if (whitted_max_component(refraction_weight) > wf_cutoff && whitted_refraction_dir(sp, d, eta, dir)) {
        wf_ray_slots[n_hits + i] = wf_make_ray(whitted_spawn_origin(sp, dir, wf_offset, wf_epsilon), dir,
                                               RT_INFINITY, refraction_weight, incoming.pixel, depth + 1u,
                                               WF_KIND_REFRACTION, 2u * incoming.path + 1u, 0u);
        wf_flags[n_hits + i] = 1u;
        ++refraction_rays;
    }
#endif
    // STUB: return;
    // END EXERCISE
#endif
}

void main() {
    const uint i = rt_global_index();
    if (i >= wf_input_count) return;
    shade(i, wf_hits[i]);
    rt_counter_add(RT_COUNTER_SHADOW_RAYS, shadow_rays);
    rt_counter_add(RT_COUNTER_REFLECTION_RAYS, reflection_rays);
    rt_counter_add(RT_COUNTER_REFRACTION_RAYS, refraction_rays);
    rt_counter_add(RT_COUNTER_TRANSPARENCY_RAYS, transparency_rays);
    rt_counter_add(RT_COUNTER_LIGHT_SAMPLES, light_sample_rays);
    wf_check_loop_budget();
}
