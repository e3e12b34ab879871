#version 330 core
// A decal on the cloth under each ball away from the cushions (instanced): shadow.frag
// darkens what is there. Flat on the cloth, it is thin seen from low down, so far
// cheaper than shadow.vert's box, which a ball near a cushion or rail needs.
uniform mat4 view_projection;
uniform float reach;   // m, half the decal's side
uniform float lift;    // m above the cloth, against depth fighting

in vec2 in_position;   // corner of the unit square [-1, 1]^2
in vec4 in_center;     // per instance: the ball's centre, and this shadow's share

out vec3 v_position;
flat out vec3 v_center;
flat out float v_share;

void main() {
    v_center = in_center.xyz;
    v_share = in_center.w;
    v_position = vec3(in_center.xy + in_position * reach, 0.0);  // on the cloth
    gl_Position = view_projection * vec4(v_position.xy, lift, 1.0);
}
