#version 330 core
// One ball as an impostor: a camera-facing square around it, ray-cast per pixel in
// ball.frag. Big enough to hold the sphere's silhouette (the tangent cone meets the
// square's plane at r d / sqrt(d^2 - r^2), more off the view's axis) and a pixel of
// anti-aliasing fringe.
uniform mat4 view_projection;
uniform vec3 camera_position;
uniform vec3 camera_right;
uniform vec3 camera_up;
uniform vec3 center;
uniform float radius;
uniform float pixel_angle;  // rad per pixel, vertically

in vec2 in_position;  // corner of the unit square [-1, 1]^2

out vec3 v_position;

void main() {
    float d = length(center - camera_position);
    // Off the view's axis the silhouette, seen in the square's plane, is an ellipse
    // stretched (and shifted) outwards by up to 1 / cos^2 of the angle off the axis.
    float off_axis = dot(normalize(center - camera_position), cross(camera_up, camera_right));
    float reach = radius * d / sqrt(max(d * d - radius * radius, 1e-8))
                  / max(off_axis * off_axis, 0.1) + 2.0 * d * pixel_angle;
    v_position = center + reach * (in_position.x * camera_right + in_position.y * camera_up);
    gl_Position = view_projection * vec4(v_position, 1.0);
}
