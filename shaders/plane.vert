#version 450 core
// The surface: the plane z = 0 as a fan of four triangles from the origin to points at infinity
// (w = 0), so it covers every direction down to the horizon; GL_DEPTH_CLAMP keeps the far part.
layout(location = 0) in vec4 aPosition;
uniform mat4 uViewProj;
void main() { gl_Position = uViewProj * aPosition; }
