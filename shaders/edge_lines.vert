#version 330 core
// A static mesh's edge (billiards/render/edge_lines.py) as a line over the drawing, for
// edge_lines.frag: kept if it is always drawn, or if it is a silhouette from here (one
// of its faces turned to the eye and the other away), else moved out of the picture.
// Both ends decide alike (from the edge's middle), and both give the fragments the
// whole line in window pixels, clipped where it passes behind the eye.
uniform mat4 view_projection;
uniform vec3 camera_position;
uniform vec2 viewport;  // the target's size, px

in vec3 in_position;
in vec3 in_other;
in vec3 in_normal_a;
in vec3 in_normal_b;
in float in_always;

flat out vec4 v_line;  // (x, y) of its two ends in window pixels

// Each end is moved this share of its distance towards the eye, so that the depth test
// against the surfaces it bounds passes, and fails behind a nearer surface.
const float LIFT = 0.004;
const float NEAREST_W = 1e-3;  // clip w the line is cut at, in front of the eye

vec4 lifted(vec3 point) {
    return view_projection * vec4(mix(point, camera_position, LIFT), 1.0);
}

vec2 window(vec4 clip) {
    return (clip.xy / clip.w * 0.5 + 0.5) * viewport;
}

void main() {
    vec3 middle = 0.5 * (in_position + in_other);
    vec3 to_eye = camera_position - middle;
    bool silhouette = (dot(in_normal_a, to_eye) > 0.0) != (dot(in_normal_b, to_eye) > 0.0);
    vec4 here = lifted(in_position);
    vec4 there = lifted(in_other);
    if (in_always < 0.5 && !silhouette || max(here.w, there.w) < NEAREST_W) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside: clipped away
        v_line = vec4(0.0);
        return;
    }
    // Cut at w = NEAREST_W where one end is behind the eye (alike from both ends).
    vec4 a = here, b = there;
    if (a.w < NEAREST_W) {
        a = mix(a, b, (NEAREST_W - a.w) / (b.w - a.w));
    }
    if (b.w < NEAREST_W) {
        b = mix(b, a, (NEAREST_W - b.w) / (a.w - b.w));
    }
    v_line = vec4(window(a), window(b));
    gl_Position = here;
}
