#version 450 core
// terrain/bounds.frag: flat colour lines.
uniform vec4 u_flat_color;
out vec4 o_color;
void main() { o_color = u_flat_color; }
