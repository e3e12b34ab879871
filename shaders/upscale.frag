#version 330 core
// The static scene drawn at a lower resolution (while the camera moves fast), filtered
// up to the frame's: colour and depth, both interpolated, so the shadows still find a
// smooth surface in the depth.
uniform sampler2D low_colour;
uniform sampler2D low_depth;

in vec2 v_uv;

out vec4 f_color;

void main() {
    f_color = texture(low_colour, v_uv);
    gl_FragDepth = texture(low_depth, v_uv).r;
}
