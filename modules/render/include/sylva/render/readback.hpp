#pragma once
// Pixels back to the CPU as sylva::Image (core), and screenshots through core's write_image.
// Read-back stalls the pipeline by design; use it for tests, screenshots and benchmarks.
// Rows are flipped so the returned Image has the top of the picture in row 0 (Image's
// convention), while GL's row 0 is the bottom.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/framebuffer.hpp>

#include <filesystem>

namespace sylva::render {

// Colour attachment `attachment` of `fb` (resolved first when multisampled) as a 4-channel
// float image (RGBA in [0, 1] for unorm formats). Errors: attachment out of range.
Result<Image> read_color(const Framebuffer& fb, int attachment = 0);

// Depth of `fb` as a 1-channel float image (window-space depth; reversed-Z: 1 near, 0 far).
Result<Image> read_depth(const Framebuffer& fb);

// Currently bound read framebuffer region (e.g. a window's back buffer), 4 channels.
Result<Image> read_bound_framebuffer(int x, int y, int width, int height);

// Reads colour attachment 0 and writes it (8-bit for .png/.jpg, half for .exr) atomically.
// The image's format is set to kU8 for PNG so it round-trips exactly.
Status save_screenshot(const Framebuffer& fb, const std::filesystem::path& path);

}  // namespace sylva::render
