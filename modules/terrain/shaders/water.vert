#version 450 core
// terrain/water.vert: one full-screen triangle; water.frag intersects each pixel's view ray with
// the water plane (an infinite plane has no vertices to draw).

void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  gl_Position = vec4(p, 0.5, 1.0);
}
