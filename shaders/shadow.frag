#version 330 core
#include "lighting.glsl"
// Analytic soft shadow of a sphere on whatever the table shows at this pixel: the
// static scene's depth gives the surface point, its neighbours the surface's normal
// (a decal on the cloth, shadow_decal.vert, gives its own point, facing up).
// Each lamp is a disc of angular size seen from that point, the ball another; the
// covered share of the lamp is removed from its light. Ambient light is occluded by
// the sphere's solid angle (cosine-weighted). The result is the ratio of shadowed to
// unshadowed lighting, multiplied into the framebuffer (blend ZERO, SRC_COLOR);
// display encoding is a power law, so multiplying encoded colours by the encoded
// ratio is exact.
uniform float radius;
uniform float reach;
uniform float light_radius;
uniform sampler2D scene_depth;          // the static scene's depth, resolved
uniform sampler2D settled_depth;        // and with the balls at rest drawn in
uniform mat4 inverse_view_projection;
uniform vec2 viewport;                  // px

in vec3 v_position;

flat in vec3 v_center;
flat in float v_share;

out vec4 f_color;

void main() {
    vec3 p = v_position;
    vec3 n = vec3(0.0, 0.0, 1.0);
    float depth = 0.0;
#ifndef ON_CLOTH  // a box: find the surface (a decal on the cloth, compiled with
    {               // ON_CLOTH, knows it, and pays nothing for this)
        vec2 uv = gl_FragCoord.xy / viewport;
        depth = texture(scene_depth, uv).r;
        // A ball at rest already drawn here hides the surface: no shadow falls on a ball.
        if (texture(settled_depth, uv).r < depth) {
            f_color = vec4(1.0);
            return;
        }
        vec4 world = inverse_view_projection * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        p = world.xyz / world.w;
        n = cross(dFdx(p), dFdy(p));
        n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
        if (dot(n, camera_position - p) < 0.0) {
            n = -n;
        }
    }
#endif
    vec3 to_ball = v_center - p;
    float dist = length(to_ball);
    if (depth >= 1.0 || dist > reach || dist < radius) {
        f_color = vec4(1.0);
        return;
    }
    vec3 b = to_ball / dist;
    float ball_angle = asin(min(radius / dist, 1.0));
    // Cosine-weighted occlusion of the sky by a sphere.
    float occlusion = clamp(dot(b, n) * (radius * radius) / (dist * dist), 0.0, 1.0);
    vec3 sky = ambient(n);
    vec3 lit = sky * (1.0 - occlusion);
    vec3 open = sky;
    for (int i = 0; i < LIGHTS; i++) {
        vec3 l;
        vec3 radiance = incident(i, p, l) * max(dot(n, l), 0.0);
        float light_angle = asin(min(light_radius / length(light_position[i] - p), 1.0));
        float apart = acos(clamp(dot(l, b), -1.0, 1.0));
        float small = min(ball_angle, light_angle);
        float overlap = clamp((ball_angle + light_angle - apart) / (2.0 * small), 0.0, 1.0);
        float covered = smoothstep(0.0, 1.0, overlap) * min(1.0, (ball_angle * ball_angle) / (light_angle * light_angle));
        lit += radiance * (1.0 - covered);
        open += radiance;
    }
    // Faded out towards the box's reach, so the shadow has no edge there.
    vec3 ratio = mix(lit / max(open, vec3(1e-6)), vec3(1.0), smoothstep(0.6 * reach, reach, dist));
    f_color = vec4(pow(clamp(ratio, 0.0, 1.0), vec3(v_share / 2.2)), 1.0);
}
