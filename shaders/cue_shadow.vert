#version 330 core
// The cue's shadow: a decal on the cloth over `rect` (the stick's outline seen from
// above, widened by its softest penumbra, cut to the cloth), for cue_shadow.frag.
uniform mat4 view_projection;
uniform vec4 rect;   // x0, y0, x1, y1 on the cloth, m
uniform float lift;  // m above the cloth, against depth fighting

in vec2 in_position;  // corner of the unit square [-1, 1]^2

out vec2 v_cloth;

void main() {
    v_cloth = mix(rect.xy, rect.zw, 0.5 * in_position + 0.5);
    gl_Position = view_projection * vec4(v_cloth, lift, 1.0);
}
