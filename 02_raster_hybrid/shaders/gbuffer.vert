#version 450 core
// G-buffer pass, vertex shader: projects the triangle soup with the camera of rt::camera_ray, so that the pixel
// centres GL samples are the points primary rays go through (docs/shading.md, "Primary rays").
//
// In camera space (x along right, y along up, z along forward, the distance in front of the eye), a primary ray
// through image position (px, py) has ndc_x = 2 px / W - 1 = x / (z h a) and ndc_y = 1 - 2 py / H = y / (z h)
// (perspective, h = tan(yfov / 2), a = aspect), or x / xmag and y / ymag (orthographic). GL samples pixel (i, j)
// at ndc 2 (i + 0.5) / size - 1, so:
//  - y is negated: GL's row j becomes image row j (row 0 at the top), the way rt::Image stores it;
//  - `jitter` = 2 (offset - 0.5) / size shifts the image so the sample at the pixel centre is the one at `offset`
//    inside the pixel (--spp, common/app/pixel_samples.h);
//  - depth is reversed (1 near, 0 at infinity) with glClipControl(GL_ZERO_TO_ONE) and a 32-bit float depth buffer:
//    perspective depth = near / z keeps float precision at every distance and needs no far plane.
layout(location = 0) in vec3 position;

uniform vec3 eye;
uniform vec3 right;
uniform vec3 up;
uniform vec3 forward;
uniform int orthographic;
uniform vec2 scale;        // perspective: 1 / (h a), 1 / h; orthographic: 1 / xmag, 1 / ymag
uniform vec2 jitter;
uniform float near;        // perspective: the near plane (tiny: rays start at the eye)
uniform float far;         // orthographic: beyond the scene

void main() {
    const vec3 p = position - eye;
    const float x = dot(p, right), y = dot(p, up), z = dot(p, forward);
    if (orthographic != 0)
        gl_Position = vec4(x * scale.x - jitter.x, -y * scale.y - jitter.y, 1.0 - z / far, 1.0);
    else
        gl_Position = vec4(x * scale.x - jitter.x * z, -y * scale.y - jitter.y * z, near, z);
}
