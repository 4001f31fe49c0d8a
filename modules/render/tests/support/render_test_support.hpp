#pragma once
// Helpers shared by the render module's tests (linked into every render test executable).

#include <sylva/core/image.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/shader_library.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace sylva::render::test {

// <test executable dir>/test_output/render: where tests leave PNGs for a person to look at.
std::filesystem::path output_dir();

// Writes an image as PNG into output_dir() (failures only logged: inspection aid, not a check).
void save_for_inspection(const Image& image, std::string_view name);

// Single-sample RGBA8 + float depth target; asserts creation succeeds.
Framebuffer make_target(int width, int height, int samples = 0);

// Builds a program or fails the calling test with the compiler message.
Program build_or_fail(std::initializer_list<std::string_view> stages, const ShaderDefines& defines = {});

// Largest absolute channel difference between two equally sized images (inf if sizes differ).
float max_abs_diff(const Image& a, const Image& b);

// Number of pixels whose RGB equals `rgb` within `tolerance` per channel.
int count_color(const Image& image, float r, float g, float b, float tolerance = 0.5f / 255.0f);

}  // namespace sylva::render::test
