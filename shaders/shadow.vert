#version 330 core
// The box round each ball (instanced) that its shadow can fall in: shadow.frag finds
// the table's surface seen at each pixel of it (cloth, cushion or rail) and darkens it.
// A moving ball casts one at each of several points of its path over the open
// shutter, each with its share of the darkening (multiplied, the shares make a
// blurred shadow).
uniform mat4 view_projection;
uniform float reach;   // m, half the box's side

in vec3 in_position;   // corner of the unit cube [-1, 1]^3
in vec4 in_center;     // per instance: the ball's centre, and this shadow's share

flat out vec3 v_center;
flat out float v_share;

void main() {
    v_center = in_center.xyz;
    v_share = in_center.w;
    gl_Position = view_projection * vec4(in_center.xyz + in_position * reach, 1.0);
}
