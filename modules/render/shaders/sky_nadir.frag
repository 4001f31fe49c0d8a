#version 450 core
// The sky dome within 30 degrees of the nadir, per pixel (sky_dome.hpp): there the table's
// column follows the azimuth's fade-out (sky.glsl), a curve no spoke follows, and with the sun
// below the horizon neighbouring columns differ a hundredfold, too much to interpolate.
#include "render/lib/sky.glsl"

in vec3 v_direction;
out vec4 o_color;

void main() {
  o_color = vec4(sky_color(normalize(v_direction)), 1.0);
}
