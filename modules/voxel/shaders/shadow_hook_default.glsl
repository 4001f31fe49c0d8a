// Default shadow hook: the render core's cascaded shadow maps (render/lib/shadows.glsl, bound by
// the host with ShadowMaps::bind; VoxelRenderer binds an all-zero "disabled" block when none is
// bound or receive_shadows is off, so the lookup then returns 1 = lit).
// VoxelRenderer::set_shadow_receiver replaces the text registered as "voxel/shadow_hook.glsl".
#ifndef SYLVA_VOXEL_SHADOW_HOOK_GLSL
#define SYLVA_VOXEL_SHADOW_HOOK_GLSL
#include "render/lib/shadows.glsl"
float voxel_shadow(vec3 rel_pos, vec3 normal) { return sylva_shadow(rel_pos, normal); }
#endif
