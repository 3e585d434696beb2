#version 330 core
// The rig's backdrop in two passes. u_mode 0: a soft vertical gradient and a millimetre grid on the base
// plate, opaque; it depends only on the view, so it is drawn once and copied each frame. u_mode 1: the
// field lines of the two repelling magnets (two opposed 2-D dipoles: the lines are level sets of the summed
// stream function psi = (m x r) / |r|^2), brighter when the magnets are close and the repulsion strong,
// premultiplied over the copy, in a box round the magnets (they fade out within u_field_reach of them).

in vec2 v_world;
uniform vec2 u_viewport;
uniform float u_px_per_m;
uniform vec3 u_bg_top;
uniform vec3 u_bg_bottom;
uniform vec3 u_grid;
uniform vec3 u_field;
uniform vec4 u_plate;        // base plate: x0, y0, x1, y1 [m]
uniform vec2 u_mag_cart;     // centre of the cart's magnet [m]
uniform vec2 u_mag_fixed;    // centre of the fixed magnet [m]
uniform float u_field_gain;  // 0..1, from the magnetic force
uniform float u_view_top;    // world y of the top edge [m]
uniform float u_view_bottom;
uniform int u_mode;          // 0 the backdrop, 1 the field lines
uniform float u_field_reach; // [m] the field lines are gone this far from the nearer magnet
out vec4 frag;

float grid_line(float coord, float spacing, float width_px) {
    float f = abs(fract(coord / spacing + 0.5) - 0.5) * spacing * u_px_per_m;   // distance to a line [px]
    return 1.0 - smoothstep(0.5 * width_px - 0.5, 0.5 * width_px + 0.5, f);
}

float psi_dipole(vec2 p, vec2 c, vec2 m) {
    vec2 r = p - c;
    return (m.x * r.y - m.y * r.x) / max(dot(r, r), 1e-8);
}

void main() {
    if (u_mode == 1) {
        // Field lines of the repelling pair: like poles face each other across the gap.
        vec2 m1 = vec2(0.0, -1.0), m2 = vec2(0.0, 1.0);
        float psi = psi_dipole(v_world, u_mag_cart, m1) + psi_dipole(v_world, u_mag_fixed, m2);
        float k = 0.05;     // inverse spacing of the level sets [m]
        float s = psi * k;
        float fw = max(fwidth(s), 1e-6);
        float line = 1.0 - smoothstep(0.0, 1.2 * fw, abs(fract(s + 0.5) - 0.5));
        float d = min(length(v_world - u_mag_cart), length(v_world - u_mag_fixed));
        float near = exp(-d / 0.018) * (1.0 - smoothstep(0.7 * u_field_reach, u_field_reach, d));
        float core = smoothstep(0.004, 0.008, d);            // no moire inside the magnets
        float density = clamp(1.0 - fw * 2.5, 0.0, 1.0);     // fade where the lines crowd below a pixel
        float a = line * near * core * density * (0.25 + 0.55 * u_field_gain);
        frag = vec4(u_field * a, a);
        return;
    }
    float t = clamp((v_world.y - u_view_bottom) / max(u_view_top - u_view_bottom, 1e-6), 0.0, 1.0);
    vec3 col = mix(u_bg_bottom, u_bg_top, t);

    // Base plate with a millimetre grid (10 mm lines stronger).
    bool on_plate = v_world.x > u_plate.x && v_world.x < u_plate.z && v_world.y > u_plate.y && v_world.y < u_plate.w;
    if (on_plate) {
        col = mix(col, u_grid, 0.10);
        float minor = max(grid_line(v_world.x, 0.001, 1.0), grid_line(v_world.y, 0.001, 1.0));
        float major = max(grid_line(v_world.x, 0.010, 1.2), grid_line(v_world.y, 0.010, 1.2));
        float minor_vis = clamp((u_px_per_m * 0.001 - 2.5) / 3.0, 0.0, 1.0);   // only when 1 mm >= ~3 px
        col = mix(col, u_grid, 0.10 * minor * minor_vis);
        col = mix(col, u_grid, 0.28 * major);
    }

    frag = vec4(col, 1.0);
}
