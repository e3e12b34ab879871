#version 330 core
// The box round each ball (instanced) that its shadow can fall in: shadow.frag finds
// the table's surface seen at each pixel of it (cloth, cushion or rail) and darkens it.
// An instance is a straight stretch of the ball's path over the open shutter (start =
// end when it rests), with its share of the shutter; shadow.frag averages along it.
uniform mat4 view_projection;
uniform float reach;   // m, how far the shadow reaches from the ball's centre
uniform float radius;  // m, the ball's

in vec3 in_position;   // corner of the unit cube [-1, 1]^3
in vec4 in_start;      // per instance: the stretch's start, and its share of the shutter
in vec3 in_end;        // and its end

out vec3 v_position;  // unused: shadow.frag finds the surface in the depth
flat out vec3 v_start;
flat out vec3 v_end;
flat out float v_share;
flat out float v_reach;

void main() {
    v_start = in_start.xyz;
    v_end = in_end;
    v_share = in_start.w;
    // A shadow falls below the lamps' light: on what lies under the ball's middle, down
    // to the cloth (so the box is a slab, thin seen from low down).
    vec3 lowest = min(in_start.xyz, in_end);
    vec3 highest = max(in_start.xyz, in_end);
    // A ball in the air (issue 45) casts its shadow further: reach grows by twice its
    // height over the cloth, so the cloth under it stays within 0.5 reach, unfaded.
    v_reach = reach + 2.0 * max(highest.z - radius, 0.0);
    float top = highest.z + 0.5 * radius;
    float bottom = min(max(lowest.z - v_reach, -0.01), top);
    vec3 low = vec3(lowest.xy - v_reach, bottom);
    vec3 high = vec3(highest.xy + v_reach, top);
    v_position = mix(low, high, 0.5 * in_position + 0.5);
    gl_Position = view_projection * vec4(v_position, 1.0);
}
