#version 400 core
// The static scene drawn at a lower resolution (while the camera moves), filtered up to
// the frame's (or copied at its own): colour and depth, both interpolated, so the
// shadows still find a smooth surface in the depth.
//
// With SMOOTH_EDGES, its edges are smoothed on the way (a cut-down FXAA, Lottes 2009's
// console variant): the green of the four texels round the pixel (one textureGather)
// gives the edge's direction, and the colour is the mean of two taps along it, reaching
// further along an edge nearer a row or a column (whose steps are longer). Away from
// edges the two taps meet at the pixel (a plain bilinear tap twice). It costs two
// texture operations more than a plain upscale (the full FXAA's eight cost llvmpipe
// +35-45% of a moving frame, multisampling the low drawing 2x its drawing 4.5x).
uniform sampler2D low_colour;
uniform sampler2D low_depth;

in vec2 v_uv;

out vec4 f_color;

#ifdef SMOOTH_EDGES
// How far the taps reach along an edge, in low texels at most (each is a quarter of the
// direction's length clamped to this); FXAA's least reduction of a short direction and
// its share of the brightness.
const float SPAN = 8.0;
const float REACH = 0.25;
const float REDUCE_MIN = 1.0 / 128.0;
const float REDUCE_MUL = 1.0 / 8.0;
#endif

void main() {
    gl_FragDepth = texture(low_depth, v_uv).r;
#ifdef SMOOTH_EDGES
    // The green of the texels (0,1), (1,1), (1,0), (0,0) of the bilinear footprint.
    vec4 g = textureGather(low_colour, v_uv, 1);
    // Along the edge: across the gradient of the four.
    vec2 dir = vec2((g.z + g.w) - (g.x + g.y), (g.x + g.w) - (g.y + g.z));
    float reduce = max((g.x + g.y + g.z + g.w) * (0.25 * REDUCE_MUL), REDUCE_MIN);
    float shortest = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
    vec2 step = clamp(dir * shortest, -SPAN, SPAN) * (REACH / vec2(textureSize(low_colour, 0)));
    f_color = 0.5 * (texture(low_colour, v_uv - step) + texture(low_colour, v_uv + step));
#else
    f_color = texture(low_colour, v_uv);
#endif
}
