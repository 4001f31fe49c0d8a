// Default shadow hook: everything lit. VoxelRenderer::set_shadow_receiver replaces the text
// registered as "voxel/shadow_hook.glsl" with the render core's cascaded-shadow lookup.
#ifndef SYLVA_VOXEL_SHADOW_HOOK_GLSL
#define SYLVA_VOXEL_SHADOW_HOOK_GLSL
float voxel_shadow(vec3 rel_pos, vec3 normal) { return 1.0; }
#endif
