#version 330 core
// Static meshes (table, room, lamp): world-space vertices with a colour and material.
uniform mat4 view_projection;

in vec3 in_position;
in vec3 in_normal;
in vec3 in_color;
in vec4 in_material;  // specular, shininess, emissive, pattern

out vec3 v_position;
out vec3 v_normal;
out vec3 v_color;
out vec4 v_material;

void main() {
    v_position = in_position;
    v_normal = in_normal;
    v_color = in_color;
    v_material = in_material;
    gl_Position = view_projection * vec4(in_position, 1.0);
}
