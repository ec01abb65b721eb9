#version 450 core
// Primary rays for the stages that trace them (03-05): one per pixel through the sample position
// wf_sample_offset inside it, exactly as rt::camera_ray (camera.glsl is its twin), written to wf_rays_in[pixel].
#include "wavefront.glsl"
#include "scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= wf_image_size.x || p.y >= wf_image_size.y) return;
    const uint pixel = uint(p.y * wf_image_size.x + p.x);
    precise float x = float(p.x) + wf_sample_offset.x;
    precise float y = float(p.y) + wf_sample_offset.y;
    const Ray ray = camera_ray(rt_camera, wf_image_size.x, wf_image_size.y, x, y);
    wf_rays_in[pixel] = wf_make_ray(ray.origin, ray.direction, RT_INFINITY, vec3(1.0), pixel, 0u, WF_KIND_PRIMARY);
}
