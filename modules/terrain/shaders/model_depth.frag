#version 450 core
// terrain/model_depth.frag: shadow-map pass of the general model (depth comes from model.vert).
void main() {}
