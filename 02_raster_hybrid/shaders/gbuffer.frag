#version 450 core
// G-buffer pass, fragment shader: the nearest triangle at each pixel centre. gl_PrimitiveID counts the triangles
// of the single glDrawArrays over the soup, so it is the triangle's index; + 1 leaves 0 for "no triangle".
layout(location = 0) out uint triangle_id;

void main() {
    triangle_id = uint(gl_PrimitiveID) + 1u;
}
