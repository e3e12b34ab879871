#version 330 core
// (lighting.glsl shades what is below the cloth by the light through `hole`)
#define IN_HOLE
#include "lighting.glsl"
// Ray-cast sphere: exact silhouette, per-pixel normal, and an analytic coverage
// fringe one pixel wide, so the balls are anti-aliased without multisampling.
// Motion blur (ball.frag draws a sharp ball) as one continuous streak: a pixel is
// covered by the share of the open shutter during which the ball covers its ray,
// found exactly on the path (straight between its points, evenly in time) as the
// roots of a quadratic per segment, and box-filtered over the pixel by averaging
// that share over radii half a pixel either side of the ball's; it is coloured as
// the ball looked along that ray at instants spread evenly over that span of
// time (one per few pixels its surface moves, up to SHADED), which moves smoothly from pixel to pixel. No discrete instants: no copies or
// rings at any speed, and the streak's brightness along the path is a plateau with
// ramps at its ends. Output is premultiplied (blend ONE, ONE_MINUS_SRC_ALPHA); balls
// are drawn far to near, so the fringe or streak of a nearer ball blends over the one
// behind.
const int PATH = 5;
const int SHADED = 4;  // instants shaded per pixel, at most: one per SHADE_STEP px
const float SHADE_STEP = 6.0;  // px the surface moves between shaded instants, about
const int FRINGE = 2;  // radii averaged across the pixel
uniform mat4 view_projection;
uniform vec3 path[PATH];   // the centre over the open shutter, evenly in time
uniform vec4 turns[PATH];  // the body -> world turn there (quaternions x, y, z, w)
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
    // A ball sinking into a pocket goes into the dark: below the cloth only the lamps'
    // light that comes in through the hole reaches it (lighting.glsl's through_hole);
    // the liner closes round it, darker from the moment it leaves the cloth and black
    // once it has sunk 2 radii (it is taken away at 4: billiards.trajectory.DROP_GONE),
    // and what is below the cloth the darker the deeper, black a radius down.
    float sunk = clamp((radius - centre.z) / (2.0 * radius), 0.0, 1.0);
    return color * (1.0 - sunk) * (1.0 - clamp(-p.z / radius, 0.0, 1.0));
}

// The texture's u, v at body-frame direction `body` (see billiards.render.textures).
vec2 texel(vec3 body) {
    return vec2(atan(body.z, body.x) / (2.0 * PI), asin(clamp(body.y, -1.0, 1.0)) / PI + 0.5);
}

// The centre at `along` the path (in its segments' units, 0 to PATH - 1).
vec3 centre_at(float along) {
    int i = clamp(int(along), 0, PATH - 2);
    return mix(path[i], path[i + 1], along - float(i));
}

// The share of the path (in its segments' units, 0 to PATH - 1) along which the ball
// can cover this pixel's ray: where the ray passes within `reach` of the centre,
// a quadratic in the path's parameter on each straight segment.
vec2 reachable(vec3 dir, float reach) {
    float first = float(PATH);
    float last = -1.0;
    for (int i = 0; i < PATH - 1; i++) {
        vec3 w0 = path[i] - camera_position;
        vec3 v = path[i + 1] - path[i];
        float dv = dot(dir, v);
        float dw = dot(dir, w0);
        float a = dot(v, v) - dv * dv;
        float b = 2.0 * (dot(w0, v) - dw * dv);
        float c = dot(w0, w0) - dw * dw - reach * reach;
        float lo = 0.0;
        float hi = 1.0;
        if (a < 1e-12) {  // the segment runs along the ray (or has no length)
            if (c > 0.0) {
                continue;
            }
        } else {
            float disc = b * b - 4.0 * a * c;
            if (disc < 0.0) {
                continue;
            }
            float root = sqrt(disc);
            lo = max((-b - root) / (2.0 * a), 0.0);
            hi = min((-b + root) / (2.0 * a), 1.0);
            if (lo > hi) {
                continue;
            }
        }
        first = min(first, float(i) + lo);
        last = max(last, float(i) + hi);
    }
    return vec2(first, last);
}

// The turn at `along` the path (normalised linear blend between its points).
vec4 turn_at(float along) {
    int i = clamp(int(along), 0, PATH - 2);
    vec4 q1 = turns[i + 1] * (dot(turns[i], turns[i + 1]) < 0.0 ? -1.0 : 1.0);
    return normalize(mix(turns[i], q1, along - float(i)));
}

// The share of the open shutter (0 to 1) during which this pixel's ray passes within
// `reach` of the centre: the lengths of the spans each straight segment gives, summed.
float within(vec3 dir, float reach) {
    float total = 0.0;
    for (int i = 0; i < PATH - 1; i++) {
        vec3 w0 = path[i] - camera_position;
        vec3 v = path[i + 1] - path[i];
        float dv = dot(dir, v);
        float dw = dot(dir, w0);
        float a = dot(v, v) - dv * dv;
        float b = 2.0 * (dot(w0, v) - dw * dv);
        float c = dot(w0, w0) - dw * dw - reach * reach;
        if (a < 1e-12) {  // the segment runs along the ray (or has no length)
            total += c > 0.0 ? 0.0 : 1.0;
            continue;
        }
        float disc = b * b - 4.0 * a * c;
        if (disc < 0.0) {
            continue;
        }
        float root = sqrt(disc);
        float lo = max((-b - root) / (2.0 * a), 0.0);
        float hi = min((-b + root) / (2.0 * a), 1.0);
        total += max(hi - lo, 0.0);
    }
    return total / float(PATH - 1);
}

void main() {
    vec3 dir = normalize(v_position - camera_position);
    // A pixel's width (m) at the ball: the fringe's and the texture's scale.
    float pixel = length(path[PATH / 2] - camera_position) * pixel_angle;
    // Most of the quad is off the streak: out at once where not even the fringe is.
    vec2 outer = reachable(dir, radius + 0.5 * pixel);
    if (outer.y < outer.x) {
        discard;
    }
    float covered = 0.0;
    for (int j = 0; j < FRINGE; j++) {
        covered += within(dir, radius + pixel * ((float(j) + 0.5) / float(FRINGE) - 0.5));
    }
    covered /= float(FRINGE);
    if (covered <= 0.0) {
        discard;
    }
    // When the ball is on this ray (or, in the fringe, nearest to it).
    vec2 span = reachable(dir, radius);
    if (span.y < span.x) {
        span = outer;
    }
    vec3 sum = vec3(0.0);
    float nearest = 1.0;
    // The surface moves this many pixels between the shaded instants: the texture is
    // read that much blurrier, so the instants do not show as copies of its print.
    // (the centre's step, or, for a spinning ball, its surface's: r times its turn)
    float travel = length(centre_at(span.y) - centre_at(span.x));
    float turned = 2.0 * acos(clamp(abs(dot(turn_at(span.x), turn_at(span.y))), 0.0, 1.0));
    float moved_px = max(travel, radius * turned) / max(pixel, 1e-9);
    int shaded = clamp(int(ceil(moved_px / SHADE_STEP)), 2, SHADED);
    float step_px = moved_px / float(shaded);
    float texels = float(textureSize(ball_texture, 0).x) * pixel / (2.0 * PI * radius);
    float level = log2(max(texels * (1.0 + step_px), 1.0));
    for (int j = 0; j < shaded; j++) {
        float along = mix(span.x, span.y, (float(j) + 0.5) / float(shaded));
        int i = clamp(int(along), 0, PATH - 2);
        float f = along - float(i);
        vec3 centre = mix(path[i], path[i + 1], f);
        vec4 q = turn_at(along);
        vec3 to_center = centre - camera_position;
        float ahead = dot(dir, to_center);
        float miss = sqrt(max(dot(to_center, to_center) - ahead * ahead, 0.0));
        float depth_in = sqrt(max(radius * radius - miss * miss, 0.0));
        vec3 p = camera_position + dir * (ahead - depth_in);
        vec3 n = normalize(p - centre);
        vec2 uv = texel(unturn(q, n));
        vec3 albedo = textureLod(ball_texture, vec2(fract(uv.x), uv.y), level).rgb;
        sum += encode(lit(p, n, dir, centre, albedo));
        vec4 clip = view_projection * vec4(p, 1.0);
        nearest = min(nearest, clip.z / clip.w * 0.5 + 0.5);
    }
    gl_FragDepth = nearest;
    float alpha = min(covered, 1.0);
    f_color = vec4(sum / float(shaded) * alpha, alpha);
}
