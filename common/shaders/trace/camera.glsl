// GLSL twin of rt::camera_ray (common/trace/shading.h), float version. The camera comes as the std140/std430
// struct GpuCamera of common/gpu/pipeline/gpu_scene.h; tan(yfov / 2) is computed on the CPU (std::tan) so the result
// matches the C++ one.
#include "rt_math.glsl"

#define RT_PROJECTION_PERSPECTIVE 0
#define RT_PROJECTION_ORTHOGRAPHIC 1

struct Camera {
    vec3 position; int projection;
    vec3 right;    float tan_half_fov;
    vec3 up;       float aspect;       // 0 = width / height
    vec3 forward;  float xmag;
    float ymag; float znear; float zfar; float yfov;
};

struct Ray {
    vec3 origin;
    vec3 direction;
    float tmax;
};

Ray make_ray(vec3 origin, vec3 direction, float tmax) {
    Ray r;
    r.origin = origin;
    r.direction = direction;
    r.tmax = tmax;
    return r;
}

// Primary ray through image position (x, y) in pixels (pixel centres at +0.5), y down.
Ray camera_ray(Camera cam, int width, int height, float x, float y) {
    precise float aspect = cam.aspect > 0.0 ? cam.aspect : float(width) / float(height);
    precise float ndc_x = 2.0 * x / float(width) - 1.0;
    precise float ndc_y = 1.0 - 2.0 * y / float(height);
    Ray ray;
    ray.tmax = RT_INFINITY;
    if (cam.projection == RT_PROJECTION_ORTHOGRAPHIC) {
        precise vec3 o = cam.position + cam.right * (ndc_x * cam.xmag) + cam.up * (ndc_y * cam.ymag);
        ray.origin = o;
        ray.direction = cam.forward;
    } else {
        const float h = cam.tan_half_fov;
        ray.origin = cam.position;
        precise vec3 d = cam.right * (ndc_x * h * aspect) + cam.up * (ndc_y * h) + cam.forward;
        ray.direction = rt_normalize(d);
    }
    return ray;
}
