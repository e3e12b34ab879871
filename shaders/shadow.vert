#version 330 core
// A decal on the cloth under each ball (instanced); shadow.frag darkens what is there.
// A moving ball casts one at each point of its path over the open shutter, each with
// its share of the darkening (multiplied, the shares make a blurred shadow).
uniform mat4 view_projection;
uniform float reach;   // m, half the decal's side
uniform float lift;    // m above the cloth, against depth fighting

in vec2 in_position;   // corner of the unit square [-1, 1]^2
in vec4 in_center;     // per instance: the ball's centre, and this decal's share

out vec3 v_position;
flat out vec3 v_center;
flat out float v_share;

void main() {
    v_center = in_center.xyz;
    v_share = in_center.w;
    v_position = vec3(in_center.xy + in_position * reach, lift);
    gl_Position = view_projection * vec4(v_position, 1.0);
}
