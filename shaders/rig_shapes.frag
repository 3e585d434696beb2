#version 330 core
// Shades one rig shape from its signed distance d (negative inside), antialiased over one pixel.
//
// Styles (v_shape.w):
//   0 flat: fill, with an outline of width v_shape.z in v_line
//   1 metal: like 0, with a cylindrical highlight across the shape (rails, spring wire, rods)
//   2 sphere: radial light from the upper left (discs, the unbalance mass, the cart body's bevel)
//   3 glow: the fill fades out over v_p2.x beyond the edge (impact flash, magnet halo)
//   4 hatched: diagonal stripes of v_line over the fill (fixed ground, walls)

in vec2 v_world;
flat in vec2 v_p0;
flat in vec2 v_p1;
flat in vec2 v_p2;
flat in vec4 v_shape;
flat in vec4 v_fill;
flat in vec4 v_line;

uniform float u_px_per_m;

out vec4 frag;

float sd_capsule(vec2 p, vec2 a, vec2 b, float r, out float across) {
    vec2 pa = p - a, ba = b - a;
    float h = clamp(dot(pa, ba) / max(dot(ba, ba), 1e-12), 0.0, 1.0);
    vec2 q = pa - ba * h;
    vec2 n = normalize(vec2(-ba.y, ba.x) + vec2(1e-9, 0.0));
    across = dot(q, n) / max(r, 1e-9);   // -1 .. 1 across the wire
    return length(q) - r;
}

float sd_box(vec2 p, vec2 c, vec2 half_size, float r) {
    vec2 q = abs(p - c) - half_size + vec2(r);
    return length(max(q, 0.0)) + min(max(q.x, q.y), 0.0) - r;
}

float sd_triangle(vec2 p, vec2 p0, vec2 p1, vec2 p2) {
    vec2 e0 = p1 - p0, e1 = p2 - p1, e2 = p0 - p2;
    vec2 v0 = p - p0, v1 = p - p1, v2 = p - p2;
    vec2 pq0 = v0 - e0 * clamp(dot(v0, e0) / dot(e0, e0), 0.0, 1.0);
    vec2 pq1 = v1 - e1 * clamp(dot(v1, e1) / dot(e1, e1), 0.0, 1.0);
    vec2 pq2 = v2 - e2 * clamp(dot(v2, e2) / dot(e2, e2), 0.0, 1.0);
    float s = sign(e0.x * e2.y - e0.y * e2.x);
    vec2 d = min(min(vec2(dot(pq0, pq0), s * (v0.x * e0.y - v0.y * e0.x)),
                     vec2(dot(pq1, pq1), s * (v1.x * e1.y - v1.y * e1.x))),
                 vec2(dot(pq2, pq2), s * (v2.x * e2.y - v2.y * e2.x)));
    return -sqrt(d.x) * sign(d.y);
}

void main() {
    int kind = int(v_shape.x + 0.5);
    int style = int(v_shape.w + 0.5);
    float r = v_shape.y;
    float px = 1.0 / u_px_per_m;   // one pixel in metres
    float across = 0.0;
    vec2 rel = vec2(0.0);          // position inside the shape, -1..1 per axis
    float d;
    if (kind == 0) {
        d = sd_capsule(v_world, v_p0, v_p1, r, across);
        rel = vec2(0.0, across);
    } else if (kind == 1) {
        d = sd_box(v_world, v_p0, v_p1, r);
        rel = (v_world - v_p0) / max(v_p1, vec2(1e-9));
    } else if (kind == 2) {
        float dist = length(v_world - v_p0);
        d = dist - r;
        if (v_p1.x > 0.0) d = max(d, v_p1.x - dist);   // a ring
        rel = (v_world - v_p0) / max(r, 1e-9);
    } else {
        d = sd_triangle(v_world, v_p0, v_p1, v_p2);
    }

    vec3 col = v_fill.rgb;
    float alpha = v_fill.a;
    if (style == 1) {
        float a = (kind == 1) ? rel.y : across;
        float hl = exp(-12.0 * (a - 0.35) * (a - 0.35));
        col = col * (0.72 + 0.28 * (1.0 - abs(a))) + vec3(0.35) * hl;
    } else if (style == 2) {
        vec2 l = rel - vec2(-0.35, 0.40);
        float spec = exp(-5.0 * dot(l, l));
        col = col * (0.80 + 0.20 * (1.0 - length(rel))) + vec3(0.22) * spec;
    } else if (style == 4) {
        float s = (v_world.x + v_world.y) * u_px_per_m / 7.0;
        float stripe = smoothstep(0.35, 0.5, abs(fract(s) - 0.5));
        col = mix(col, v_line.rgb, 0.45 * stripe);
    }

    // Outline band just inside the edge.
    float w = v_shape.z;
    if (w > 0.0 && style != 4) {
        float inner = smoothstep(-w - 0.5 * px, -w + 0.5 * px, d);
        col = mix(col, v_line.rgb, inner * v_line.a);
    }
    float cover = clamp(0.5 - d / px, 0.0, 1.0);
    if (style == 3) {
        float g = max(v_p2.x, 1e-9);
        float halo = d > 0.0 ? exp(-3.0 * d / g) * (1.0 - smoothstep(0.8 * g, g, d)) : 1.0;
        cover = max(cover, halo);
    }
    alpha *= cover;
    if (alpha <= 0.002) discard;
    frag = vec4(col * alpha, alpha);   // premultiplied
}
