#version 330 core
#include "lighting.glsl"
// Analytic soft shadow of a sphere: each lamp is a disc of angular size seen from
// the cloth point, the ball another; the covered share of the lamp is removed from
// its light. Ambient light is occluded by the sphere's solid angle (cosine-weighted).
// The result is the ratio of shadowed to unshadowed cloth lighting, multiplied into
// the framebuffer (blend ZERO, SRC_COLOR); display encoding is a power law, so
// multiplying encoded colours by the encoded ratio is exact.
uniform float radius;
uniform float light_radius;

in vec3 v_position;
flat in vec3 v_center;
flat in float v_share;

out vec4 f_color;

void main() {
    vec3 p = vec3(v_position.xy, 0.0);
    vec3 to_ball = v_center - p;
    float dist = length(to_ball);
    vec3 b = to_ball / dist;
    float ball_angle = asin(min(radius / dist, 1.0));
    // Cosine-weighted occlusion of the sky by a sphere (up-facing receiver).
    float occlusion = clamp(b.z * (radius * radius) / (dist * dist), 0.0, 1.0);
    vec3 lit = ambient_sky * (1.0 - occlusion);
    vec3 open = ambient_sky;
    for (int i = 0; i < LIGHTS; i++) {
        vec3 l;
        vec3 radiance = incident(i, p, l) * max(l.z, 0.0);
        float light_angle = asin(min(light_radius / length(light_position[i] - p), 1.0));
        float apart = acos(clamp(dot(l, b), -1.0, 1.0));
        float small = min(ball_angle, light_angle);
        float overlap = clamp((ball_angle + light_angle - apart) / (2.0 * small), 0.0, 1.0);
        float covered = smoothstep(0.0, 1.0, overlap) * min(1.0, (ball_angle * ball_angle) / (light_angle * light_angle));
        lit += radiance * (1.0 - covered);
        open += radiance;
    }
    vec3 ratio = lit / max(open, vec3(1e-6));
    f_color = vec4(pow(clamp(ratio, 0.0, 1.0), vec3(v_share / 2.2)), 1.0);
}
