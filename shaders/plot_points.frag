#version 330 core
in vec2 v_local;
in float v_alpha;
uniform vec4 u_color;
uniform float u_half;
out vec4 frag;
void main() {
    float cover = clamp(u_half + 0.5 - length(v_local), 0.0, 1.0);
    float a = u_color.a * v_alpha * cover;
    if (a <= 0.003) discard;
    frag = vec4(u_color.rgb, a);
}
