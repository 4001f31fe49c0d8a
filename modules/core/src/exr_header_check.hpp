// A structural check of an OpenEXR file's headers, run before OpenImageIO opens it.
//
// Why: OpenEXR trusts the sizes a header declares. A 4 KB file whose attribute claims 1.8 GB makes
// the library allocate 1.8 GB before it notices that the bytes are not there (found by the
// image_map fuzz target, fuzz/README.md), and a data window of 2^31 lines makes it allocate an
// offset table of that many entries. Every such size is bounded by the file itself: an attribute's
// value and a part's offset table (8 bytes per chunk) must fit in the bytes the file holds. This
// check walks the headers (never the pixels) and refuses what cannot fit, naming the attribute.
// The library reads known types with their own readers, not by the declared size, so the walk
// also refuses a fixed-size type declaring another size, and a channel list or preview image that
// does not fill its declared bytes: otherwise the library would read the rest of the header out
// of step with this walk (the fuzz target found exactly that).
#pragma once

#include <sylva/core/result.hpp>

#include <filesystem>
#include <string_view>

namespace sylva::detail {

// When the file at `path` starts with the OpenEXR magic number (0x762f3101), walks every header
// (single or multi-part); any other file passes untouched. Refuses (kCorrupt) an
// attribute whose declared size is negative or larger than the rest of the file, a name longer
// than the format allows, a header that never ends; refuses (kLimit) a data window wider or taller
// than `max_side` and a part whose offset table could not fit in the file. Messages start with
// `display`. Reads at most the headers; never allocates more than one attribute name.
Status check_exr_header(const std::filesystem::path& path, std::string_view display, int max_side);

}  // namespace sylva::detail
