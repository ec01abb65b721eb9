#version 450 core
// Primary rays for a stage that traces them (03 with --primary trace): one per pixel through the sample position
// wf_sample_offset inside it, exactly as rt::camera_ray (camera.glsl is its twin). Slot s of the batch is the pixel
// wf_tile_pixel(wf_tile_first * 64 + s) (8x8 tiles, Morton order inside), so compaction gives the queue that order.
#include "wavefront.glsl"
#include "common/shaders/trace/scene.glsl"

layout(local_size_x = 64) in;

void main() {
    const uint slot = rt_global_index();
    if (slot >= wf_input_count) return;
    ivec2 p;
    if (!wf_tile_pixel(wf_tile_first * 64u + slot, p)) {
        wf_flags[slot] = 0u;
        return;
    }
    const uint pixel = uint(p.y * wf_image_size.x + p.x);
    precise float x = float(p.x) + wf_sample_offset.x;
    precise float y = float(p.y) + wf_sample_offset.y;
    const Ray ray = camera_ray(rt_camera, wf_image_size.x, wf_image_size.y, x, y);
    wf_ray_slots[slot] = wf_make_ray(ray.origin, ray.direction, RT_INFINITY, vec3(1.0), pixel, 0u, WF_KIND_PRIMARY,
                                     1u, 0u);
    wf_flags[slot] = 1u;
}
