#version 330 core
// A plain copy of the texture, no blending: the shape Mesa's llvmpipe recognises as a blit and draws at
// memory speed (a blended, colour-modulated ImGui image costs it about three times as much per pixel).
in vec2 v_uv;
uniform sampler2D u_tex;
out vec4 frag;

void main() { frag = texture(u_tex, v_uv); }
