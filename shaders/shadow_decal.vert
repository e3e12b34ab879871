#version 330 core
// A decal on the cloth under each ball away from the cushions (instanced): shadow.frag
// darkens what is there. Flat on the cloth, it is thin seen from low down, so far
// cheaper than shadow.vert's box, which a ball near a cushion or rail needs. An
// instance is a straight stretch of the ball's path (start = end when it rests).
uniform mat4 view_projection;
uniform float reach;   // m, how far the shadow reaches from the ball's centre
uniform float lift;    // m above the cloth, against depth fighting

in vec2 in_position;   // corner of the unit square [-1, 1]^2
in vec4 in_start;      // per instance: the stretch's start, and its share of the shutter
in vec3 in_end;        // and its end

out vec3 v_position;
flat out vec3 v_start;
flat out vec3 v_end;
flat out float v_share;
flat out float v_reach;  // on the cloth: reach

void main() {
    v_start = in_start.xyz;
    v_end = in_end;
    v_share = in_start.w;
    v_reach = reach;
    vec2 low = min(in_start.xy, in_end.xy) - reach;
    vec2 high = max(in_start.xy, in_end.xy) + reach;
    v_position = vec3(mix(low, high, 0.5 * in_position + 0.5), 0.0);  // on the cloth
    gl_Position = view_projection * vec4(v_position.xy, lift, 1.0);
}
