#version 330 core
// Instanced 2-D shapes of the rig, drawn as signed distance fields. One instance = one shape; the vertex
// shader expands a quad over the shape's bounding box (world metres), the fragment shader shades it.
//
// a_shape.x (kind): 0 capsule p0-p1 (radius r), 1 rounded box (centre p0, half size p1, corner r),
//                   2 disc or ring (centre p0, outer r, inner p1.x), 3 triangle p0 p1 p2
// a_shape.y: r;  a_shape.z: outline width [m];  a_shape.w: style (see rig_shapes.frag)
// a_p2 for kinds 0-2: (glow width [m], unused)

layout(location = 0) in vec2 a_p0;
layout(location = 1) in vec2 a_p1;
layout(location = 2) in vec2 a_p2;
layout(location = 3) in vec4 a_shape;
layout(location = 4) in vec4 a_fill;
layout(location = 5) in vec4 a_line;

uniform vec2 u_center;      // world point at the middle of the viewport [m]
uniform float u_px_per_m;   // zoom
uniform vec2 u_viewport;    // [px]

out vec2 v_world;
flat out vec2 v_p0;
flat out vec2 v_p1;
flat out vec2 v_p2;
flat out vec4 v_shape;
flat out vec4 v_fill;
flat out vec4 v_line;

void main() {
    int kind = int(a_shape.x + 0.5);
    float r = a_shape.y;
    vec2 lo, hi;
    float glow = (kind == 3) ? 0.0 : a_p2.x;
    if (kind == 0) {
        lo = min(a_p0, a_p1) - vec2(r);
        hi = max(a_p0, a_p1) + vec2(r);
    } else if (kind == 1) {
        lo = a_p0 - a_p1;
        hi = a_p0 + a_p1;
    } else if (kind == 2) {
        lo = a_p0 - vec2(r);
        hi = a_p0 + vec2(r);
    } else {
        lo = min(min(a_p0, a_p1), a_p2);
        hi = max(max(a_p0, a_p1), a_p2);
    }
    float pad = 2.0 / u_px_per_m + glow;
    lo -= vec2(pad);
    hi += vec2(pad);
    // Triangle strip corners from the vertex id: (lo,lo) (hi,lo) (lo,hi) (hi,hi).
    vec2 corner = vec2((gl_VertexID & 1) != 0 ? hi.x : lo.x, (gl_VertexID & 2) != 0 ? hi.y : lo.y);
    v_world = corner;
    v_p0 = a_p0;
    v_p1 = a_p1;
    v_p2 = a_p2;
    v_shape = a_shape;
    v_fill = a_fill;
    v_line = a_line;
    vec2 ndc = (corner - u_center) * u_px_per_m / (0.5 * u_viewport);
    gl_Position = vec4(ndc, 0.0, 1.0);
}
