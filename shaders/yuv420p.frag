#version 330 core
// gpu_shader5: textureGather of any component (core in GLSL 4.00).
#extension GL_ARB_gpu_shader5 : require
// The finished RGBA picture as yuv420p's planes, BT.709, limited ("tv") range: Y in
// 16..235, U (Cb) and V (Cr) in 16..240, chroma from the mean of each 2x2 block. One
// fragment a 2x2 block (the targets are half the picture's size each way): its four Y
// values, the top two to one target and the bottom two to another (each a row of the
// Y plane when read back: rows alternate between them), its U and its V. Values are
// rounded to the nearest code, as an encoder's converter does; the targets are UNORM8,
// which rounds to nearest and clamps as they store.
uniform sampler2D picture;  // RGBA8, as drawn (its row 0 is the picture's top)
uniform vec2 texel;  // 1 / the picture's size

layout(location = 0) out vec2 f_luma_top;
layout(location = 1) out vec2 f_luma_bottom;
layout(location = 2) out float f_cb;
layout(location = 3) out float f_cr;

const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);  // BT.709's Kr, Kg, Kb
const float CB_SCALE = 1.8556;  // 2 (1 - Kb)
const float CR_SCALE = 1.5748;  // 2 (1 - Kr)

void main() {
    // The block's four texels meet at this point: each gather gets one component of
    // them, as (x0, y1), (x1, y1), (x1, y0), (x0, y0), y0 the upper row.
    vec2 corner = (2.0 * floor(gl_FragCoord.xy) + 1.0) * texel;
    vec4 red = textureGather(picture, corner, 0);
    vec4 green = textureGather(picture, corner, 1);
    vec4 blue = textureGather(picture, corner, 2);
    vec4 luma = LUMA.r * red + LUMA.g * green + LUMA.b * blue;
    vec4 y = (16.0 + 219.0 * luma) / 255.0;
    f_luma_top = y.wz;
    f_luma_bottom = y.xy;
    float mean_luma = 0.25 * (luma.x + luma.y + luma.z + luma.w);
    float mean_blue = 0.25 * (blue.x + blue.y + blue.z + blue.w);
    float mean_red = 0.25 * (red.x + red.y + red.z + red.w);
    f_cb = (128.0 + 224.0 * (mean_blue - mean_luma) / CB_SCALE) / 255.0;
    f_cr = (128.0 + 224.0 * (mean_red - mean_luma) / CR_SCALE) / 255.0;
}
