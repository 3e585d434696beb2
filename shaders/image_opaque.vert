#version 330 core
// An opaque image over a rectangle of display pixels (a plot's data area, the rig): four vertices from
// gl_VertexID, no vertex buffer.
uniform vec4 u_rect;           // x0, y0, x1, y1 [display px]
uniform vec4 u_uv;             // u0, v0, u1, v1 at (x0, y0) and (x1, y1)
uniform vec2 u_display_pos;    // ImGui's display rectangle
uniform vec2 u_display_size;
out vec2 v_uv;

void main() {
    vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : 0.0, (gl_VertexID & 2) != 0 ? 1.0 : 0.0);
    vec2 p = mix(u_rect.xy, u_rect.zw, c);
    v_uv = mix(u_uv.xy, u_uv.zw, c);
    vec2 ndc = (p - u_display_pos) / u_display_size * 2.0 - 1.0;
    gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
}
