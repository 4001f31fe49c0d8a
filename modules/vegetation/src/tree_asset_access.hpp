#pragma once
// Module-internal access to a TreeAsset's GL objects for the slice bake (slice_bake.cpp), which
// draws the LOD0 tree with its own programs into multiple render targets.
#include <sylva/vegetation/tree_renderer.hpp>

namespace sylva::vegetation {

struct TreeAssetAccess {
  static const render::VertexArray& branch_vao(const TreeAsset& a) { return a.branch_vao_; }
  static const render::VertexArray& leaf_vao(const TreeAsset& a) { return a.leaf_vao_; }
  static const render::Buffer& branches(const TreeAsset& a) { return a.branches_; }
  static const render::Buffer& leaves(const TreeAsset& a) { return a.leaves_; }
  static const render::Texture& leaf_color(const TreeAsset& a) { return a.leaf_color_; }
  static const render::Texture& leaf_normal(const TreeAsset& a) { return a.leaf_normal_; }
  static const render::Texture& leaf_coverage(const TreeAsset& a) { return a.leaf_coverage_; }
  static const render::Texture& bark_albedo(const TreeAsset& a) { return a.bark_albedo_; }
  static const render::Texture& bark_normal(const TreeAsset& a) { return a.bark_normal_; }
  static const render::Texture& season(const TreeAsset& a) { return a.season_; }
};

}  // namespace sylva::vegetation
