#version 330 core
// One ball as an impostor, ray-cast per pixel in ball.frag: a quad facing the camera
// that holds the ball's silhouette all along its path over the open shutter (one
// point when it rests or the shutter is shut), and a pixel of anti-aliasing fringe.
// The path's points are carried through the camera onto the plane through their
// middle square to the view, so the quad covers their projections exactly; each
// point's sphere reaches r d / sqrt(d^2 - r^2) there (the tangent cone's), scaled.
const int PATH = 5;
uniform mat4 view_projection;
uniform vec3 camera_position;
uniform vec3 camera_right;
uniform vec3 camera_up;
uniform vec3 path[PATH];  // the centre over the open shutter, evenly in time
uniform float radius;
uniform float pixel_angle;  // rad per pixel, vertically

in vec2 in_position;  // corner of the unit square [-1, 1]^2

out vec3 v_position;

void main() {
    vec3 forward = cross(camera_up, camera_right);
    vec3 middle = 0.5 * (path[0] + path[PATH - 1]);
    float plane = max(dot(middle - camera_position, forward), 1e-4);
    vec2 low = vec2(1e9);
    vec2 high = vec2(-1e9);
    for (int k = 0; k < PATH; k++) {
        vec3 to_point = path[k] - camera_position;
        float depth = max(dot(to_point, forward), 1e-4);
        float d = length(to_point);
        // (off the view's axis the silhouette is stretched outwards, by up to 1 / cos^2)
        float off_axis = depth / d;
        float reach = (radius * d / sqrt(max(d * d - radius * radius, 1e-8))) * plane / depth
                      / max(off_axis * off_axis, 0.1);
        vec3 on_plane = to_point * (plane / depth);
        vec2 at = vec2(dot(on_plane, camera_right), dot(on_plane, camera_up));
        low = min(low, at - reach);
        high = max(high, at + reach);
    }
    float fringe = 2.0 * plane * pixel_angle;
    vec2 corner = mix(low - fringe, high + fringe, 0.5 * in_position + 0.5);
    v_position = camera_position + plane * forward + corner.x * camera_right + corner.y * camera_up;
    gl_Position = view_projection * vec4(v_position, 1.0);
}
