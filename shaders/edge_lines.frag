#version 330 core
// Smooths a step of the drawing where an edge's line crosses it (after Persson's
// geometric post-process anti-aliasing, 2011). A line is rasterized one pixel a column
// (one a row, if steep); the edge crosses that pixel's column `off` pixels from its
// centre (|off| <= 1/2), so the share 1/2 - |off| of the pixel lies beyond the edge,
// where the neighbour's colour is: one bilinear tap between the two, from a copy of the
// drawing, gives the pixel that mix.
uniform sampler2D picture;  // a copy of the drawing the lines are drawn over

flat in vec4 v_line;

out vec4 f_color;

void main() {
    vec2 centre = gl_FragCoord.xy;
    vec2 start = v_line.xy, run = v_line.zw - v_line.xy;
    bool flat_line = abs(run.x) >= abs(run.y);  // one pixel a column
    float off = flat_line
        ? start.y + (centre.x - start.x) * run.y / run.x - centre.y
        : start.x + (centre.y - start.y) * run.x / run.y - centre.x;
    if (abs(off) > 0.5 || dot(run, run) < 1e-6) {
        discard;
    }
    vec2 towards = flat_line ? vec2(0.0, sign(off)) : vec2(sign(off), 0.0);
    vec2 size = vec2(textureSize(picture, 0));
    f_color = texture(picture, (centre + towards * (0.5 - abs(off))) / size);
}
