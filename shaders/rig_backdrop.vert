#version 330 core
// A quad over the world rectangle u_quad (the whole view for the backdrop, a box round the magnets for
// their field lines); the fragment shader works in world coordinates.
uniform vec2 u_center;
uniform float u_px_per_m;
uniform vec2 u_viewport;
uniform vec4 u_quad;   // x0, y0, x1, y1 [m]
out vec2 v_world;
void main() {
    vec2 c = vec2((gl_VertexID & 1) != 0 ? 1.0 : 0.0, (gl_VertexID & 2) != 0 ? 1.0 : 0.0);
    v_world = mix(u_quad.xy, u_quad.zw, c);
    gl_Position = vec4((v_world - u_center) * u_px_per_m / (0.5 * u_viewport), 0.0, 1.0);
}
