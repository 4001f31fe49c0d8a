#pragma once
// The module descriptors compiled into this build (module_registry.cpp lists them under
// SYLVA_HAS_<M>, set by modules/scene/CMakeLists.txt when the module's target exists).

#include <sylva/scene/module_registry.hpp>

namespace sylva::scene::detail {

ModuleDescriptor ground_module();
ModuleDescriptor terrain_module();
ModuleDescriptor model_terrain_module();  // with the terrain module (SYLVA_HAS_TERRAIN)
ModuleDescriptor grass_module();
ModuleDescriptor vegetation_module();
ModuleDescriptor voxel_module();

}  // namespace sylva::scene::detail
