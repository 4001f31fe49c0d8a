// Tracked GPU memory (gpu_memory.hpp): the bytes counted for an owner equal the sum of the
// storage a test allocates (buffers exactly, textures level by level, render targets by sample),
// moves keep the count, destruction returns it, nested owners attribute to the innermost.
#include <sylva/render/buffer.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/texture.hpp>

#include <gtest/gtest.h>

#include <optional>
#include <utility>

namespace sylva::render {
namespace {

using GpuMemoryGl = GlTest;

std::uint64_t held(const std::string& owner, GpuMemoryKind kind) {
  const auto usage = gpu_memory_usage();
  const auto it = usage.find(owner);
  return it == usage.end() ? 0 : it->second.bytes[static_cast<int>(kind)];
}

TEST_F(GpuMemoryGl, CountsWhatATestAllocatesAndReturnsItOnDestruction) {
  const std::uint64_t total_before = gpu_memory_total();
  {
    GpuMemoryOwner owner("gpu_memory_test");
    Buffer fixed = Buffer::immutable(1000, nullptr);
    Buffer grows = Buffer::dynamic(100);
    std::vector<char> data(500, 1);
    grows.upload(data.size(), data.data());  // capacity max(500, 150) = 500
    EXPECT_EQ(held("gpu_memory_test", GpuMemoryKind::kBuffer), 1500u);

    // 64x32 RGBA8 with a full mip chain: (2048 + 512 + 128 + 32 + 8 + 2 + 1) texels x 4 bytes.
    Texture mipped = Texture::create_2d(64, 32, GL_RGBA8, mip_levels(64, 32));
    // 8x8x3 RGBA16F array, one level: 192 texels x 8 bytes.
    Texture array = Texture::create_2d_array(8, 8, 3, GL_RGBA16F);
    EXPECT_EQ(held("gpu_memory_test", GpuMemoryKind::kTexture), 2731u * 4u + 192u * 8u);
    EXPECT_EQ(mipped.storage_bytes(), 2731u * 4u);

    // 16x16 colour RGBA8 + depth 32F, 4 samples, with its single-sample resolve targets.
    auto msaa = Framebuffer::create({.width = 16, .height = 16, .color_formats = {GL_RGBA8},
                                     .depth_format = GL_DEPTH_COMPONENT32F, .samples = 4});
    ASSERT_TRUE(msaa.ok()) << msaa.error().message;
    EXPECT_EQ(held("gpu_memory_test", GpuMemoryKind::kRenderTarget), 256u * 8u * 4u + 256u * 8u);
    EXPECT_EQ(held("gpu_memory_test", GpuMemoryKind::kTexture), 2731u * 4u + 192u * 8u) << "attachments are render targets";

    // A move keeps one count; a moved-from buffer holds none.
    Buffer moved = std::move(fixed);
    EXPECT_EQ(held("gpu_memory_test", GpuMemoryKind::kBuffer), 1500u);
    {
      GpuMemoryOwner inner("gpu_memory_test_inner");
      Buffer b = Buffer::immutable(64, nullptr);
      EXPECT_EQ(held("gpu_memory_test_inner", GpuMemoryKind::kBuffer), 64u);
      EXPECT_EQ(held("gpu_memory_test", GpuMemoryKind::kBuffer), 1500u);
    }
    EXPECT_EQ(held("gpu_memory_test_inner", GpuMemoryKind::kBuffer), 0u);
    EXPECT_GE(gpu_memory_peak_total(), gpu_memory_total());
    EXPECT_GT(gpu_memory_total(), total_before);
  }
  for (GpuMemoryKind kind : {GpuMemoryKind::kBuffer, GpuMemoryKind::kTexture, GpuMemoryKind::kRenderTarget}) {
    EXPECT_EQ(held("gpu_memory_test", kind), 0u) << gpu_memory_kind_name(kind);
  }
  EXPECT_EQ(gpu_memory_total(), total_before);
  EXPECT_GE(gpu_memory_usage().at("gpu_memory_test").peak_total, 1500u + 2731u * 4u + 192u * 8u);
}

TEST_F(GpuMemoryGl, AllocationsOutsideAnyOwnerCountAsOther) {
  const std::uint64_t before = held("other", GpuMemoryKind::kBuffer);
  Buffer b = Buffer::immutable(4096, nullptr);
  EXPECT_EQ(held("other", GpuMemoryKind::kBuffer), before + 4096u);
}

}  // namespace
}  // namespace sylva::render
