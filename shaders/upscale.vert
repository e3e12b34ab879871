#version 330 core
// The whole frame, for upscale.frag.
in vec2 in_position;  // corner of the unit square [-1, 1]^2

out vec2 v_uv;

void main() {
    v_uv = 0.5 * in_position + 0.5;
    gl_Position = vec4(in_position, 0.0, 1.0);
}
