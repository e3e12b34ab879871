#version 330 core
// A decal on the cloth under each ball (instanced); shadow.frag darkens what is there.
uniform mat4 view_projection;
uniform float reach;   // m, half the decal's side
uniform float lift;    // m above the cloth, against depth fighting

in vec2 in_position;   // corner of the unit square [-1, 1]^2
in vec3 in_center;     // per instance: the ball's centre

out vec3 v_position;
flat out vec3 v_center;

void main() {
    v_center = in_center;
    v_position = vec3(in_center.xy + in_position * reach, lift);
    gl_Position = view_projection * vec4(v_position, 1.0);
}
