#version 330 core
// The box round each ball (instanced) that its shadow can fall in: shadow.frag finds
// the table's surface seen at each pixel of it (cloth, cushion or rail) and darkens it.
// A moving ball casts one at each of several points of its path over the open
// shutter, each with its share of the darkening (multiplied, the shares make a
// blurred shadow).
uniform mat4 view_projection;
uniform float reach;   // m, half the box's side
uniform float radius;  // m, the ball's

in vec3 in_position;   // corner of the unit cube [-1, 1]^3
in vec4 in_center;     // per instance: the ball's centre, and this shadow's share

out vec3 v_position;  // unused: shadow.frag finds the surface in the depth
flat out vec3 v_center;
flat out float v_share;

void main() {
    v_center = in_center.xyz;
    v_share = in_center.w;
    // A shadow falls below the lamps' light: on what lies under the ball's middle, down
    // to the cloth (so the box is a slab, thin seen from low down).
    vec3 c = in_center.xyz;
    float top = c.z + 0.5 * radius;
    float bottom = min(max(c.z - reach, -0.01), top);
    vec3 low = vec3(c.xy - reach, bottom);
    vec3 high = vec3(c.xy + reach, top);
    v_position = mix(low, high, 0.5 * in_position + 0.5);
    gl_Position = view_projection * vec4(v_position, 1.0);
}
