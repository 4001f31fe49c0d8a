#pragma once
// merge_bake_shares with the one-process shortcut (bake.cpp): `in_place` patches the single share
// where it lies and renames it to `out` (saving a copy of the whole file); the share is consumed.

#include <sylva/terrain/bake.hpp>

namespace sylva::terrain::detail {

Result<BakeReport> merge_shares(const std::vector<std::filesystem::path>& shares, const std::filesystem::path& out,
                                const BuildControl& control, bool in_place);

}  // namespace sylva::terrain::detail
