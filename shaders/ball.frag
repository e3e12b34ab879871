#version 330 core
#include "lighting.glsl"
// Ray-cast sphere: exact silhouette, per-pixel normal, and an analytic coverage
// fringe one pixel wide, so the balls are anti-aliased without multisampling.
// Motion blur: the ball is drawn at `samples` instants evenly over the open shutter
// (its centre and turn along the path's points, exact at them), and each pixel
// averages what it saw at them: a fast ball is a streak, a resting one (samples = 1)
// is sharp. Output is premultiplied (blend ONE, ONE_MINUS_SRC_ALPHA); balls are drawn
// far to near, so the fringe or streak of a nearer ball blends over the one behind.
const int PATH = 5;
uniform mat4 view_projection;
uniform vec3 path[PATH];   // the centre over the open shutter, evenly in time
uniform vec4 turns[PATH];  // the body -> world turn there (quaternions x, y, z, w)
uniform int samples;
uniform float radius;
uniform float pixel_angle;
uniform sampler2D ball_texture;  // sRGB: sampled (and mipmapped) in linear space

in vec3 v_position;

out vec4 f_color;

const float PI = 3.14159265358979;

// v turned by the inverse of unit quaternion q (world -> body).
vec3 unturn(vec4 q, vec3 v) {
    vec3 u = -q.xyz;
    return v + 2.0 * cross(u, cross(u, v) + q.w * v);
}

vec3 lit(vec3 p, vec3 n, vec3 dir, vec3 centre, vec3 albedo) {
    vec3 color = shade(p, n, albedo, 0.3, 400.0);
    // Polished resin reflects the room: the bright lamp above, the dim room around.
    vec3 r = reflect(dir, n);
    float fresnel = 0.04 + 0.96 * pow(1.0 - max(dot(n, -dir), 0.0), 5.0);
    color += fresnel * mix(ambient_ground, ambient_sky, r.z * 0.5 + 0.5) * 1.5;
    // A ball sinking into a pocket goes into the dark: the liner closes round it and
    // the hole's edge hides the lamps, black once it has sunk 3 radii (it is taken
    // away at 4: billiards.trajectory.DROP_GONE), and what is below the cloth the
    // darker the deeper, so it never vanishes while it can be seen.
    float sunk = smoothstep(0.0, 1.0, clamp((radius - centre.z) / (3.0 * radius), 0.0, 1.0));
    return color * (1.0 - sunk) * (1.0 - clamp(-p.z / (1.5 * radius), 0.0, 1.0));
}

// The texture's u, v at body-frame direction `body` (see billiards.render.textures).
vec2 texel(vec3 body) {
    return vec2(atan(body.z, body.x) / (2.0 * PI), asin(clamp(body.y, -1.0, 1.0)) / PI + 0.5);
}

void main() {
    vec3 dir = normalize(v_position - camera_position);
    vec3 sum = vec3(0.0);
    float covered = 0.0;
    float nearest = 1.0;
    for (int k = 0; k < samples; k++) {
        // The instant's place along the path (piecewise linear between its points).
        float along = samples == 1 ? 0.5 * float(PATH - 1)
                                   : (float(k) + 0.5) / float(samples) * float(PATH - 1);
        int i = min(int(along), PATH - 2);
        float f = along - float(i);
        vec3 centre = mix(path[i], path[i + 1], f);
        vec4 q1 = turns[i + 1] * (dot(turns[i], turns[i + 1]) < 0.0 ? -1.0 : 1.0);
        vec4 q = normalize(mix(turns[i], q1, f));

        vec3 to_center = centre - camera_position;
        float ahead = dot(dir, to_center);
        float miss = sqrt(max(dot(to_center, to_center) - ahead * ahead, 0.0));
        float pixel = ahead * pixel_angle;  // one pixel's width at the ball, in m
        float coverage = clamp((radius - miss) / pixel + 0.5, 0.0, 1.0);
        if (coverage <= 0.0) {
            continue;
        }
        // The hit point; in the fringe outside the sphere, the nearest point of its rim.
        float depth_in = sqrt(max(radius * radius - miss * miss, 0.0));
        vec3 p = camera_position + dir * (ahead - depth_in);
        vec3 n = normalize(p - centre);
        vec2 uv = texel(unturn(q, n));
        vec3 albedo;
        if (samples == 1) {
            // Two parametrisations of u, cut at different meridians; use the one
            // without the wrap in this pixel quad so the mipmap level stays right
            // across the seam.
            float u_a = fract(uv.x);
            float u_b = fract(uv.x + 0.5) - 0.5;
            uv.x = fwidth(u_a) <= fwidth(u_b) + 1e-5 ? u_a : u_b;
            albedo = texture(ball_texture, uv).rgb;
        } else {
            // Inside a streak the texture is smeared anyway: a mip level from the
            // ball's size on screen, as no derivatives hold across the instants.
            float across = radius / max(pixel, 1e-9);  // the ball's radius in pixels
            float level = log2(max(float(textureSize(ball_texture, 0).x) / (PI * across), 1.0));
            albedo = textureLod(ball_texture, vec2(fract(uv.x), uv.y), level).rgb;
        }
        sum += encode(lit(p, n, dir, centre, albedo)) * coverage;
        covered += coverage;
        vec4 clip = view_projection * vec4(p, 1.0);
        nearest = min(nearest, clip.z / clip.w * 0.5 + 0.5);
    }
    if (covered <= 0.0) {
        discard;
    }
    float count = float(samples);
    gl_FragDepth = nearest;
    f_color = vec4(sum / count, covered / count);
}
