#pragma once
// merge_bake_shares and bake_share with the one-process shortcut (bake.cpp): `in_place` patches the
// single share where it lies and renames it to `out` (saving a copy of the whole file); the share
// is consumed. That share is a temporary this process wrote a moment before, so its blobs carry no
// checksums (`blob_checksums` = false) and the in-place merge does not verify them: FNV-1a runs
// byte by byte (~0.5 GB/s on the 2-core VM), and the share's checksum plus its verification were
// two of the three passes over every mesh byte of a one-process bake (the chunk file's own
// checksum, the third, is what the in-memory build's save also computes).

#include <sylva/terrain/bake.hpp>

namespace sylva::terrain::detail {

Result<BakeReport> bake_share(HeightField field, const std::filesystem::path& share_file, const BakeOptions& options,
                              bool blob_checksums);

Result<BakeReport> merge_shares(const std::vector<std::filesystem::path>& shares, const std::filesystem::path& out,
                                const BuildControl& control, bool in_place);

}  // namespace sylva::terrain::detail
