#version 330 core
// (lighting.glsl shades what is below the cloth by the light through `hole`)
#define IN_HOLE
#include "lighting.glsl"
// Ray-cast sphere: exact silhouette, per-pixel normal, and an analytic coverage
// fringe one pixel wide, so the balls are anti-aliased without multisampling. A
// resting (or slow) ball, or any with the shutter shut; ball_blur.frag draws the rest.
// Output is premultiplied (blend ONE, ONE_MINUS_SRC_ALPHA); balls are drawn far to
// near, so the fringe of a nearer ball blends over the ball behind it.
uniform mat4 view_projection;
uniform vec3 center;
uniform mat3 rotation;           // body -> world
uniform float radius;
uniform float pixel_angle;
uniform sampler2D ball_texture;  // sRGB: sampled (and mipmapped) in linear space

in vec3 v_position;

out vec4 f_color;

const float PI = 3.14159265358979;

void main() {
    vec3 dir = normalize(v_position - camera_position);
    vec3 to_center = center - camera_position;
    float along = dot(dir, to_center);
    float miss = sqrt(max(dot(to_center, to_center) - along * along, 0.0));
    float pixel = along * pixel_angle;  // one pixel's width at the ball, in m
    float coverage = clamp((radius - miss) / pixel + 0.5, 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    // The hit point; in the fringe outside the sphere, the nearest point of its rim.
    float depth_in = sqrt(max(radius * radius - miss * miss, 0.0));
    vec3 p = camera_position + dir * (along - depth_in);
    vec3 n = normalize(p - center);

    // Equirectangular lookup about the body y axis (see billiards.render.textures).
    vec3 body = transpose(rotation) * n;
    float v = asin(clamp(body.y, -1.0, 1.0)) / PI + 0.5;
    float u = atan(body.z, body.x) / (2.0 * PI);
    // Two parametrisations of u, cut at different meridians; use the one without the
    // wrap in this pixel quad so the mipmap level stays right across the seam.
    float u_a = fract(u);
    float u_b = fract(u + 0.5) - 0.5;
    u = fwidth(u_a) <= fwidth(u_b) + 1e-5 ? u_a : u_b;
    vec3 albedo = texture(ball_texture, vec2(u, v)).rgb;

    vec3 color = shade(p, n, albedo, 0.3, 400.0);
    // Polished resin reflects the room: the bright lamp above, the dim room around.
    vec3 view = -dir;
    vec3 r = reflect(dir, n);
    float fresnel = 0.04 + 0.96 * pow(1.0 - max(dot(n, view), 0.0), 5.0);
    color += fresnel * mix(ambient_ground, ambient_sky, r.z * 0.5 + 0.5) * 1.5;
    // A ball sinking into a pocket goes into the dark: below the cloth only the lamps'
    // light that comes in through the hole reaches it (lighting.glsl's through_hole);
    // the liner closes round it, darker from the moment it leaves the cloth and black
    // once it has sunk 2 radii (it is taken away at 4: billiards.trajectory.DROP_GONE),
    // and what is below the cloth the darker the deeper, black a radius down.
    float sunk = clamp((radius - center.z) / (2.0 * radius), 0.0, 1.0);
    color *= (1.0 - sunk) * (1.0 - clamp(-p.z / radius, 0.0, 1.0));

    vec4 clip = view_projection * vec4(p, 1.0);
    gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
    f_color = vec4(encode(color) * coverage, coverage);
}
