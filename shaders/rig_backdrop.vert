#version 330 core
// A full-viewport quad; the fragment shader works in world coordinates.
uniform vec2 u_center;
uniform float u_px_per_m;
uniform vec2 u_viewport;
out vec2 v_world;
void main() {
    vec2 ndc = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
    v_world = u_center + ndc * 0.5 * u_viewport / u_px_per_m;
    gl_Position = vec4(ndc, 0.0, 1.0);
}
