#version 330 core
#include "lighting.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec3 v_color;
in vec4 v_material;

out vec4 f_color;

float hash(vec2 p) {
    return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453);
}

// Procedural surface detail, cheap enough for a CPU rasterizer.
vec3 pattern(vec3 albedo, float kind, vec3 p) {
    if (kind > 0.5 && kind < 1.5) {  // wood grain
        float grain = sin(140.0 * (p.x + p.y + 1.7 * p.z) + 3.0 * sin(11.0 * (p.x - p.y)));
        return albedo * (0.88 + 0.12 * grain);
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
    if (kind > 2.5) {  // cloth: a faint weave so the bed does not look like plastic
        float weave = hash(floor(p.xy * 900.0));
        return albedo * (0.96 + 0.08 * weave);
    }
    return albedo;
}

void main() {
    vec3 n = normalize(v_normal);
    vec3 albedo = pattern(v_color, v_material.w, v_position);
    vec3 lit = shade(v_position, n, albedo, v_material.x, v_material.y);
    vec3 color = mix(lit, albedo * 1.6, v_material.z);
    f_color = vec4(encode(color), 1.0);
}
