#version 330 core
#include "lighting.glsl"
// Analytic soft shadow of a sphere on whatever the table shows at this pixel: the
// static scene's depth gives the surface point, its neighbours the surface's normal
// (a decal on the cloth, shadow_decal.vert, gives its own point, facing up).
// Each lamp is a disc of angular size seen from that point, the ball another; the
// covered share of the lamp is removed from its light. Ambient light is occluded by
// the sphere's solid angle (cosine-weighted). A moving ball's shadow is averaged over
// the time it spends along one straight stretch of its path (an instance each, with
// its share of the open shutter): at a few instants spread evenly over the part of
// the stretch within reach of this point, which moves smoothly from pixel to pixel,
// so the blurred shadow is one continuous streak, never copies. The result is the
// ratio of shadowed to unshadowed lighting, multiplied into the framebuffer (blend
// ZERO, SRC_COLOR);
// display encoding is a power law, so multiplying encoded colours by the encoded
// ratio is exact.
uniform float radius;
uniform float light_radius;
uniform sampler2D scene_depth;          // the static scene's depth, resolved
uniform sampler2D settled_depth;        // and with the balls at rest drawn in
uniform mat4 inverse_view_projection;
uniform vec2 viewport;                  // px

in vec3 v_position;

flat in vec3 v_start;
flat in vec3 v_end;
flat in float v_share;
flat in float v_reach;                  // m, how far this ball's shadow reaches

out vec4 f_color;

const int SPREAD = 4;  // instants averaged along a moving ball's stretch
// Along a stretch, the ball's distance is taken as at least this many radii: right
// under the ball the shadow is black over a vanishing area (the ball fills the sky), a
// peak that a few instants would catch now and then as dark lines; its average over
// the stretch is smooth, and so is this.
const float CORE = 1.8;

// The ratio of shadowed to open light at surface point p (normal n) from a ball at
// `centre` (1 out of reach), its distance taken as at least `core`.
vec3 shadow_ratio(vec3 p, vec3 n, vec3 centre, float core) {
    vec3 to_ball = centre - p;
    float dist = length(to_ball);
    if (dist > v_reach || dist < radius) {
        return vec3(1.0);
    }
    to_ball *= max(core / dist, 1.0);
    dist = max(dist, core);
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
    return mix(lit / max(open, vec3(1e-6)), vec3(1.0), smoothstep(0.6 * v_reach, v_reach, dist));
}

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
    if (depth >= 1.0) {
        f_color = vec4(1.0);
        return;
    }
    vec3 ratio;
    vec3 along = v_end - v_start;
    float a = dot(along, along);
    if (a < 1e-12) {  // at rest, or the shutter shut
        ratio = shadow_ratio(p, n, v_start, radius);
    } else {
        // The part of the stretch within reach of p: |start + t along - p| <= reach.
        vec3 w = v_start - p;
        float b = dot(w, along);
        float c = dot(w, w) - v_reach * v_reach;
        float disc = b * b - a * c;
        if (disc <= 0.0) {
            f_color = vec4(1.0);
            return;
        }
        float root = sqrt(disc);
        float lo = clamp((-b - root) / a, 0.0, 1.0);
        float hi = clamp((-b + root) / a, 0.0, 1.0);
        if (hi <= lo) {
            f_color = vec4(1.0);
            return;
        }
        vec3 darkened = vec3(0.0);
        for (int k = 0; k < SPREAD; k++) {
            float t = mix(lo, hi, (float(k) + 0.5) / float(SPREAD));
            darkened += vec3(1.0) - shadow_ratio(p, n, v_start + t * along, CORE * radius);
        }
        // Out of reach for the rest of the stretch: no darkening then.
        ratio = vec3(1.0) - darkened / float(SPREAD) * (hi - lo);
    }
    f_color = vec4(pow(clamp(ratio, 0.0, 1.0), vec3(v_share / 2.2)), 1.0);
}
