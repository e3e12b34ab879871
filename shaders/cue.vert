#version 330 core
// The cue: its lathe mesh (billiards.render.cue, local x from the tip back along the
// stick) placed by `model`. Each vertex is pushed out along its normal by most of a
// pixel, so that the fringe cue.frag fades is outside the stick's true edge as much as
// inside it (the cue is drawn without multisampling, over the finished picture).
uniform mat4 view_projection;
uniform mat4 model;
uniform vec3 camera_position;
uniform float pixel_angle;  // rad per pixel, vertically

in vec3 in_position;
in vec3 in_normal;
in vec3 in_color;
in vec4 in_material;  // specular, shininess, emissive, pattern

out vec3 v_position;
out vec3 v_normal;
out vec3 v_color;
out vec4 v_material;

void main() {
    vec3 world = (model * vec4(in_position, 1.0)).xyz;
    vec3 normal = normalize(mat3(model) * in_normal);
    world += normal * 0.6 * pixel_angle * length(world - camera_position);
    v_position = world;
    v_normal = normal;
    v_color = in_color;
    v_material = in_material;
    gl_Position = view_projection * vec4(world, 1.0);
}
