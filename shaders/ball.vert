#version 330 core
// One ball: a unit sphere in the body frame, turned and moved to its place.
uniform mat4 view_projection;
uniform vec3 center;
uniform mat3 rotation;  // body -> world
uniform float radius;

in vec3 in_position;  // unit sphere: also the body-frame normal
in vec2 in_texcoord_0;

out vec3 v_position;
out vec3 v_normal;
out vec2 v_texcoord;

void main() {
    v_normal = rotation * in_position;
    v_position = center + radius * v_normal;
    v_texcoord = in_texcoord_0;
    gl_Position = view_projection * vec4(v_position, 1.0);
}
