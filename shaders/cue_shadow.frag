#version 330 core
// The cue's soft shadow on the cloth, as the balls' are multiplied in (blend ZERO,
// SRC_COLOR; the display encoding is a power law, so the encoded ratio is exact). The
// lamp's shades are taken as one disc of radius `lamp_radius` at `lamp_height` right
// over each point: a stick of radius r whose axis is h over the cloth hides it over
// a band r wide, blurred by a penumbra R h / (H - h) each side; where the penumbra is
// wider than the stick, the band is lighter by as much (the shadow's depth times its
// width stays the stick's). Near the tip, low over the cloth, the shadow is narrow and
// dark; along the raised butt, wide and faint. Round at both ends.
uniform vec3 tip;  // the axis's two ends, m
uniform vec3 butt;
uniform vec2 radii;  // the stick's radius at the tip and at the butt, m
uniform float lamp_radius;
uniform float lamp_height;  // m over the cloth

in vec2 v_cloth;

out vec4 f_color;

// Of the light, the share the stick's full shadow takes away: the lamp's spots, not
// the room's fill (a ball's shadow under it is about as dark).
const float STRENGTH = 0.6;

void main() {
    vec2 along = butt.xy - tip.xy;
    float t = clamp(dot(v_cloth - tip.xy, along) / max(dot(along, along), 1e-12), 0.0, 1.0);
    float off = length(v_cloth - (tip.xy + t * along));
    float height = max(mix(tip.z, butt.z, t), 0.0);
    float r = mix(radii.x, radii.y, t);
    float spread = lamp_radius * height / max(lamp_height - height, 0.05) + 1e-4;
    float cover = clamp((r + spread - off) / (2.0 * spread), 0.0, 1.0);
    float ratio = 1.0 - STRENGTH * min(1.0, r / spread) * smoothstep(0.0, 1.0, cover);
    f_color = vec4(vec3(pow(ratio, 1.0 / 2.2)), 1.0);
}
