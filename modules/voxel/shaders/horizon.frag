#version 450 core
// The horizon skirt's colour: the sky at the horizon in each direction (distance_fade.glsl).
#include "voxel/distance_fade.glsl"

in vec3 v_rel_pos;
out vec4 o_color;

void main() { o_color = vec4(voxel_horizon_color(v_rel_pos), 1.0); }
