#version 450 core
// Trace pass: one thread per ray of wf_rays_in (reflection and refraction rays, or primary rays in stages that
// trace them): the closest hit goes to the hit queue for the next shade pass; a ray that leaves the scene brings
// the background, weighted by its path weight. The stage's traversal (trace_closest) is included before this file
// by rt::gpu::Wavefront.
#include "wavefront.glsl"

layout(local_size_x = 64) in;

void main() {
    const uint i = rt_global_index();
    if (i < wf_input_count) {
        const WavefrontRay r = wf_rays_in[i];
        Hit hit;
        if (trace_closest(wf_ray(r), hit)) wf_push_hit(r, hit);
        else wf_accumulate(r.pixel, r.weight * rt_background);
    }
    wf_flush_tests();
}
