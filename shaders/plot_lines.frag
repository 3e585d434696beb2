#version 330 core
// Coverage of a line `u_half` pixels wide from the distance across it; straight alpha like ImGui.
in float v_across;
in float v_alpha;
uniform vec4 u_color;
uniform float u_half;
out vec4 frag;
void main() {
    float cover = clamp(u_half + 0.5 - abs(v_across), 0.0, 1.0);
    float a = u_color.a * v_alpha * cover;
    if (a <= 0.003) discard;
    frag = vec4(u_color.rgb, a);
}
