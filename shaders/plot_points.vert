#version 330 core
// Plot markers on the GPU: one instance per point, a quad of `u_half` pixels around it (+1 for
// antialiasing); the fragment shader cuts a disc. Positions in ImGui display pixels, a_p.z = opacity.
layout(location = 0) in vec4 a_p;
uniform vec2 u_display_pos;
uniform vec2 u_display_size;
uniform float u_half;
out vec2 v_local;
out float v_alpha;
void main() {
    vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
    float r = u_half + 1.0;
    vec2 p = a_p.xy + corner * r;
    v_local = corner * r;
    v_alpha = a_p.z;
    vec2 ndc = vec2((p.x - u_display_pos.x) / u_display_size.x * 2.0 - 1.0,
                    1.0 - (p.y - u_display_pos.y) / u_display_size.y * 2.0);
    gl_Position = vec4(ndc, 0.0, 1.0);
}
