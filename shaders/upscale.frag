#version 400 core
// The static scene drawn at a lower resolution (while the camera moves), filtered up to
// the frame's (or copied at its own): colour (its edges smoothed first by edges.frag,
// when asked) and depth, both interpolated, so the shadows still find a smooth surface
// in the depth.
uniform sampler2D low_colour;
uniform sampler2D low_depth;

in vec2 v_uv;

out vec4 f_color;

void main() {
    gl_FragDepth = texture(low_depth, v_uv).r;
    f_color = texture(low_colour, v_uv);
}
