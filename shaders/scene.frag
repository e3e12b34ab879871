#version 330 core
#include "lighting.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec3 v_color;
in vec4 v_material;

out vec4 f_color;

uniform vec2 table_size;  // m: the cloth between the cushion noses, [0, L] x [0, W]

// A cheap hash in [0, 1) (Dave Hoskins' hash12: no sine, which costs a CPU rasterizer).
float hash(vec2 p) {
    vec3 p3 = fract(vec3(p.xyx) * 0.1031);
    p3 += dot(p3, p3.yzx + 33.33);
    return fract((p3.x + p3.y) * p3.z);
}

// Smooth value noise in [0, 1].
float noise(vec2 p) {
    vec2 i = floor(p);
    vec2 f = p - i;
    vec2 u = f * f * (3.0 - 2.0 * f);
    return mix(mix(hash(i), hash(i + vec2(1.0, 0.0)), u.x),
               mix(hash(i + vec2(0.0, 1.0)), hash(i + vec2(1.0, 1.0)), u.x), u.y);
}

// How much of a pattern of this phase is left once a pixel averages it: 1 while a
// period spans a few pixels, 0 once it would alias (shimmer as the camera moves).
float resolved(float phase) {
    return clamp(1.5 - 2.0 * fwidth(phase), 0.0, 1.0);
}

// Wood: the grain runs along `along` (a unit axis); the cross-section coordinates
// (across, height) give the growth rings of a board sawn from a log whose axis lies
// off to one side, warped by slow noise so the rings wander; fine pores streak along
// the grain. Each board (a stretch of rail) its own log, so the boards differ.
vec3 wood(vec3 albedo, vec3 p, vec3 along, vec3 across) {
    float a = dot(p, along);
    float b = dot(p, across);
    float c = dot(p, cross(along, across));
    float board = floor(a / 5.0);  // one board to a rail
    vec2 log_axis = vec2(hash(vec2(board, 1.3)) - 0.5, hash(vec2(board, 7.1)) + 0.6) * 0.25;
    vec2 section = vec2(b, c) - log_axis;
    float figure = noise(vec2(a * 1.6, b * 45.0 + board * 5.0));  // broad streaks
    float shade = 0.82 + 0.22 * figure;
    // The finer detail only where a pixel can hold it (and only then paid for).
    float wander = 0.012 * sin(a * 2.5 + board * 3.1) * (0.6 + 0.4 * figure);
    float rings = (length(section) + wander) * 110.0;  // a ring per 9 mm
    float ring_seen = resolved(rings);
    if (ring_seen > 0.0) {
        float r = fract(rings + 0.004 * 110.0 * noise(vec2(a * 11.0, b * 30.0)));
        float ring = smoothstep(0.0, 0.6, r) * (1.0 - smoothstep(0.6, 1.0, r));
        shade *= 1.0 - 0.22 * ring * ring_seen;
    }
    float pores_seen = resolved(b * 900.0);
    if (pores_seen > 0.0) {
        shade *= 1.0 - 0.12 * noise(vec2(a * 40.0, b * 900.0)) * pores_seen;
    }
    return albedo * shade;
}

// The grain of a rail, apron or wall panel follows its length: along x beside the long
// cushions, along y beside the short ones, mitred on the diagonals at the corners.
vec3 rail_grain(vec3 p) {
    float beyond_x = max(-p.x, p.x - table_size.x);
    float beyond_y = max(-p.y, p.y - table_size.y);
    return beyond_x > beyond_y ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
}

// Procedural surface detail, cheap enough for a CPU rasterizer.
vec3 pattern(vec3 albedo, float kind, vec3 p, vec3 n) {
    if (kind > 0.5 && kind < 1.5) {  // wood, grain along the rails
        vec3 along = rail_grain(p);
        return wood(albedo, p, along, vec3(along.y, along.x, 0.0));
    }
    if (kind > 3.5) {  // wood, grain upright (legs, turned posts)
        vec3 across = normalize(vec3(-n.y, n.x, 0.0) + vec3(1e-4, 0.0, 0.0));
        return wood(albedo, p, vec3(0.0, 0.0, 1.0), across);
    }
    if (kind > 1.5 && kind < 2.5) {  // floor planks, staggered
        float row = floor(p.y / 0.16);
        float along = p.x + hash(vec2(row, 3.0)) * 1.4;
        float plank = floor(along / 1.4);
        float shade = 0.7 + 0.45 * hash(vec2(plank, row));
        float seam = step(0.03, fract(p.y / 0.16)) * step(0.006, fract(along / 1.4));
        float grain = 0.92 + 0.08 * sin(70.0 * along + 5.0 * sin(23.0 * p.y + row));
        return albedo * shade * grain * mix(0.35, 1.0, seam);
    }
    if (kind > 2.5) {  // cloth: a fine nap of fibres, faded out before it would alias
        float shade = 1.0 + 0.04 * (noise(p.xy * 90.0) - 0.5);  // tufts
        float seen = resolved(p.x * 1400.0);
        if (seen > 0.0) {
            shade += 0.06 * (noise(p.xy * vec2(1400.0, 1100.0)) - 0.5) * seen;
        }
        return albedo * shade;
    }
    return albedo;
}

void main() {
    vec3 n = normalize(v_normal);
#ifdef PATTERN
    // This program draws one kind of surface (billiards.render.renderer compiles one
    // per kind): the compiler keeps only that kind's pattern.
    vec3 albedo = pattern(v_color, PATTERN, v_position, n);
#else
    vec3 albedo = pattern(v_color, v_material.w, v_position, n);
#endif
    vec3 lit = shade(v_position, n, albedo, v_material.x, v_material.y);
    vec3 color = mix(lit, albedo * 1.6, v_material.z);
    f_color = vec4(encode(color), 1.0);
}
