// Shared lighting: Blinn-Phong from the lamp's spot lights and a room fill, in
// linear RGB; display encoding at the very end (encode()).
// Lights 0 .. LIGHTS - 2 are the lamp's spots; the last, FILL, is the room's all-round
// fill (billiards.render.renderer.Lighting holds them so). Naming the fill by its
// index, not by its cone, lets the compiler drop what it does not need from each
// light of the unrolled loops (a CPU rasterizer pays for both sides of a choice).
const int LIGHTS = 4;
const int FILL = LIGHTS - 1;
uniform vec3 light_position[LIGHTS];
uniform vec3 light_color[LIGHTS];   // linear intensity (irradiance at 1 m)
uniform float light_cone[LIGHTS];   // cos of the spot's outer half-angle; -1: all round
uniform vec3 ambient_sky;           // hemisphere ambient, from above
uniform vec3 ambient_ground;        // and from below
uniform vec3 camera_position;

// The light arriving from light i at p, per unit area facing it (spot cone included).
vec3 incident(int i, vec3 p, out vec3 l) {
    vec3 to_light = light_position[i] - p;
    float d2 = dot(to_light, to_light);
    l = to_light * inversesqrt(d2);
    float cone = light_cone[i];
    // Spots point straight down: l.z is the cosine off their axis.
    float spot = i == FILL ? 1.0 : smoothstep(cone, mix(cone, 1.0, 0.45), l.z);
    // The fill stands for light bounced off the walls and floor, a broad source, not a
    // bulb: it falls off no more within a metre of itself, and so does not blaze white
    // on the ceiling it hangs under (seen in the wide views of square and upright films).
    return light_color[i] * spot / (i == FILL ? max(d2, 1.0) : d2);
}

#ifdef IN_HOLE
// The hole a ball drops into: its centre's x, y and the liner's radius (< 0: none).
uniform vec3 hole;

// How much of the light from `to_light` (p to the light) reaches p: all of it above
// the cloth; below, only what comes in through the hole's opening (its edge softened
// over a few mm), as the rim and the liner's wall shade the rest.
float through_hole(vec3 p, vec3 to_light) {
    if (p.z >= 0.0 || hole.z < 0.0) {
        return 1.0;
    }
    vec2 crossing = p.xy + to_light.xy * (-p.z / max(to_light.z, 1e-6));
    return 1.0 - smoothstep(hole.z - 0.004, hole.z + 0.004, length(crossing - hole.xy));
}
#endif

vec3 ambient(vec3 n) {
    return mix(ambient_ground, ambient_sky, n.z * 0.5 + 0.5);
}

vec3 shade(vec3 p, vec3 n, vec3 albedo, float specular, float shininess) {
    vec3 v = normalize(camera_position - p);
    vec3 color = albedo * ambient(n);
    for (int i = 0; i < LIGHTS; i++) {
        vec3 l;
        vec3 radiance = incident(i, p, l);
#ifdef IN_HOLE
        radiance *= through_hole(p, light_position[i] - p);
#endif
        // The all-round room fill stands for light bounced off the walls and floor
        // too: wrapped, so sides facing away from the lamp (the apron, the rails'
        // outsides) are lit dimly rather than left black.
        float ndl = i == FILL ? pow(max(dot(n, l) * 0.5 + 0.5, 0.0), 2.0) : max(dot(n, l), 0.0);
        vec3 h = normalize(l + v);
        // Normalised Blinn-Phong: the highlight keeps its energy as it narrows.
        float spec = specular * (shininess + 8.0) / 25.13 * pow(max(dot(n, h), 0.0), shininess);
        color += radiance * ndl * (albedo + vec3(spec));
    }
    return color;
}

vec3 encode(vec3 linear) {
    // The exact sRGB curve: the inverse of how the textures and colours were decoded,
    // so that dark tones (pocket holes, number ink) come out as dark as they were given.
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
