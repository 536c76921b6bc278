#version 450 core
// One triangle over the whole viewport (clip-space corners (-1, -1), (3, -1), (-1, 3)), made from gl_VertexID:
// the fragment shader finds the plane from each pixel's own ray and writes 0 where the ray sees the sky, so
// every pixel is written and the frame needs no clear (src/render/renderer.cpp, drawWith).
void main() {
    gl_Position = vec4(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0, 0.0, 1.0);
}
