#version 330 core
// One triangle that covers the whole target (its corners made from gl_VertexID: no
// vertex buffer), for passes that work on every pixel of a finished picture.

void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);  // (0,0), (2,0), (0,2)
    gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
