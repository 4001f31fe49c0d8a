#version 450 core
#include "render/lib/sky.glsl"

in vec3 v_direction;
out vec4 o_color;

void main() {
  o_color = vec4(sky_color(normalize(v_direction)), 1.0);
}
