#version 330 core
// Plot curves drawn on the GPU: one instance per segment (p0 -> p1, read from the same vertex buffer at
// offsets i and i+1), expanded to a quad `u_half` pixels either side of the segment plus one pixel of
// antialiasing, with square caps so consecutive segments join without gaps. Positions are in ImGui's
// display pixels (top-left origin); a_p.z is the point's opacity (the fading trail).
layout(location = 0) in vec4 a_p0;
layout(location = 1) in vec4 a_p1;
uniform vec2 u_display_pos;
uniform vec2 u_display_size;
uniform float u_half;
out float v_across;
out float v_alpha;
void main() {
    vec2 d = a_p1.xy - a_p0.xy;
    float len = length(d);
    vec2 t = len > 1e-4 ? d / len : vec2(1.0, 0.0);
    vec2 n = vec2(-t.y, t.x);
    float w = u_half + 1.0;
    bool at_end = (gl_VertexID & 1) != 0;
    float side = (gl_VertexID & 2) != 0 ? 1.0 : -1.0;
    vec2 p = at_end ? a_p1.xy + t * (0.5 * u_half) : a_p0.xy - t * (0.5 * u_half);
    p += n * side * w;
    v_across = side * w;
    v_alpha = at_end ? a_p1.z : a_p0.z;
    vec2 ndc = vec2((p.x - u_display_pos.x) / u_display_size.x * 2.0 - 1.0,
                    1.0 - (p.y - u_display_pos.y) / u_display_size.y * 2.0);
    gl_Position = vec4(ndc, 0.0, 1.0);
}
