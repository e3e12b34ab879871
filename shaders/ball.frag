#version 330 core
#include "lighting.glsl"

uniform sampler2D ball_texture;  // sRGB: sampled (and mipmapped) in linear space

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord;

out vec4 f_color;

void main() {
    vec3 n = normalize(v_normal);
    vec3 albedo = texture(ball_texture, v_texcoord).rgb;
    vec3 color = shade(v_position, n, albedo, 0.3, 400.0);
    // Polished resin reflects the room: the bright lamp above, the dim room around.
    vec3 v = normalize(camera_position - v_position);
    vec3 r = reflect(-v, n);
    float fresnel = 0.04 + 0.96 * pow(1.0 - max(dot(n, v), 0.0), 5.0);
    vec3 room = mix(ambient_ground, ambient_sky, r.z * 0.5 + 0.5) * 1.5;
    color += fresnel * room;
    f_color = vec4(encode(color), 1.0);
}
