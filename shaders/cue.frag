#version 330 core
#include "lighting.glsl"
// The cue, lit as the table is, its edges anti-aliased without multisampling: where
// the smooth normal turns away from the eye (the silhouette) the surface fades out over
// about a pixel, by how fast n.v changes across the screen there.

in vec3 v_position;
in vec3 v_normal;
in vec3 v_color;
in vec4 v_material;

out vec4 f_color;

void main() {
    vec3 n = normalize(v_normal);
    vec3 v = normalize(camera_position - v_position);
    float facing = dot(n, v);
    float coverage = clamp(facing / max(fwidth(facing), 1e-5) + 0.5, 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    vec3 lit = shade(v_position, n, v_color, v_material.x, v_material.y);
    vec3 color = mix(lit, v_color * 1.6, v_material.z);
    // Premultiplied: blended ONE, ONE_MINUS_SRC_ALPHA over the picture.
    f_color = vec4(encode(color) * coverage, coverage);
}
