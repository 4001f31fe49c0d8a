// Procedural pixel-art block textures in the seed's cartoon style (§4.6, "kreslený vzhled").
// Each texel is a deterministic function of (texture, x, y, seed): value noise for colour
// variation, a few shapes per texture (bark stripes, log rings, leaf clusters, grass blades).

#include <sylva/voxel/block_textures.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/rng.hpp>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::voxel {

std::string_view texture_name(TextureId id) {
  static constexpr std::string_view kNames[] = {
      "stone",        "dirt",          "grass_top",     "grass_side",    "dry_grass_top", "dry_grass_side",
      "sand",         "snow",          "gravel",        "oak_bark",      "birch_bark",    "acacia_bark",
      "jungle_bark",  "log_top",       "oak_leaves",    "birch_leaves",  "acacia_leaves", "jungle_leaves",
      "bush_leaves",  "berry_leaves",  "tall_grass",    "flowers",       "lantern",       "glowstone"};
  static_assert(sizeof(kNames) / sizeof(kNames[0]) == kTextureCount);
  const int i = static_cast<int>(id);
  return i >= 0 && i < kTextureCount ? kNames[i] : "?";
}

namespace {

struct Texel {
  glm::vec3 rgb{0.0f};
  float alpha = 1.0f;
  float specular = 0.0f;
};

// Hash of a texel in [0, 1).
float rnd(int x, int y, std::uint32_t salt) {
  return static_cast<float>(hash_i32(x, y, salt) >> 8) * (1.0f / 16777216.0f);
}

// Smooth value noise with `cells` cells across the tile, wrapping so the tile repeats.
float value_noise(float u, float v, int cells, std::uint32_t salt) {
  const float fx = u * static_cast<float>(cells), fy = v * static_cast<float>(cells);
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const float tx = fx - static_cast<float>(x0), ty = fy - static_cast<float>(y0);
  auto at = [&](int x, int y) { return rnd(((x % cells) + cells) % cells, ((y % cells) + cells) % cells, salt); };
  const float sx = tx * tx * (3.0f - 2.0f * tx), sy = ty * ty * (3.0f - 2.0f * ty);
  const float a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * sx;
  const float b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * sx;
  return a + (b - a) * sy;
}

glm::vec3 rgb(int r, int g, int b) { return glm::vec3(r, g, b) / 255.0f; }

Texel leaves(float u, float v, int x, int y, std::uint32_t salt, glm::vec3 dark, glm::vec3 light, float holes) {
  Texel t;
  const float n = value_noise(u, v, 4, salt) * 0.6f + rnd(x, y, salt + 1) * 0.4f;
  t.rgb = glm::mix(dark, light, n);
  t.alpha = rnd(x, y, salt + 2) < holes ? 0.0f : 1.0f;
  t.specular = 0.25f * n;
  return t;
}

Texel bark(float u, float v, int x, int y, std::uint32_t salt, glm::vec3 base, glm::vec3 groove) {
  Texel t;
  // Vertical stripes wobbling with height.
  const float s = value_noise(u * 3.0f + 0.15f * std::sin(v * 12.0f), v * 0.5f, 4, salt);
  t.rgb = glm::mix(groove, base, std::clamp(s * 1.6f - 0.2f, 0.0f, 1.0f)) * (0.9f + 0.2f * rnd(x, y, salt + 3));
  return t;
}

Texel texel(TextureId id, int x, int y, int size, std::uint32_t salt) {
  const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
  const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);  // v = 0 at the top
  const float r = rnd(x, y, salt);
  const float n = value_noise(u, v, 4, salt + 11);
  Texel t;
  switch (id) {
    case TextureId::kStone:
      t.rgb = glm::vec3(0.45f + 0.15f * n + 0.08f * r);
      t.specular = r > 0.8f ? 0.6f : 0.15f;
      break;
    case TextureId::kDirt:
      t.rgb = glm::mix(rgb(110, 76, 48), rgb(140, 100, 64), 0.6f * n + 0.4f * r);
      break;
    case TextureId::kGrassTop:
      t.rgb = glm::mix(rgb(70, 135, 50), rgb(105, 170, 65), 0.5f * n + 0.5f * r);
      t.specular = 0.1f;
      break;
    case TextureId::kGrassSide:
    case TextureId::kDryGrassSide: {
      const bool dry = id == TextureId::kDryGrassSide;
      const float edge = 0.22f + 0.1f * rnd(x, 0, salt + 5);
      if (v < edge) {
        t.rgb = dry ? glm::mix(rgb(165, 150, 75), rgb(195, 180, 95), r) : glm::mix(rgb(70, 135, 50), rgb(105, 170, 65), r);
      } else {
        t.rgb = glm::mix(rgb(110, 76, 48), rgb(140, 100, 64), 0.6f * n + 0.4f * r);
      }
      break;
    }
    case TextureId::kDryGrassTop:
      t.rgb = glm::mix(rgb(160, 145, 72), rgb(200, 185, 100), 0.5f * n + 0.5f * r);
      break;
    case TextureId::kSand:
      t.rgb = glm::mix(rgb(210, 195, 140), rgb(235, 222, 170), 0.5f * n + 0.5f * r);
      t.specular = r > 0.9f ? 0.5f : 0.05f;
      break;
    case TextureId::kSnow:
      t.rgb = glm::vec3(0.9f + 0.08f * n);
      t.specular = 0.5f + 0.5f * r;
      break;
    case TextureId::kGravel:
      t.rgb = glm::vec3(0.35f + 0.3f * value_noise(u, v, 8, salt + 2)) * glm::vec3(1.0f, 0.97f, 0.93f);
      t.specular = 0.2f;
      break;
    case TextureId::kOakBark: t = bark(u, v, x, y, salt, rgb(110, 82, 50), rgb(65, 45, 28)); break;
    case TextureId::kAcaciaBark: t = bark(u, v, x, y, salt, rgb(120, 110, 100), rgb(85, 70, 60)); break;
    case TextureId::kJungleBark: {
      t = bark(u, v, x, y, salt, rgb(95, 70, 40), rgb(60, 45, 25));
      if (value_noise(u, v, 3, salt + 9) > 0.7f) t.rgb = glm::mix(t.rgb, rgb(70, 110, 45), 0.6f);  // moss
      break;
    }
    case TextureId::kBirchBark: {
      // Real birch bark reflects ~0.5-0.6; at 0.9 it burned out white in sunlight once tone mapped.
      t.rgb = glm::vec3(0.6f + 0.08f * r) * glm::vec3(1.0f, 0.98f, 0.94f);
      // Short dark horizontal marks.
      const int band = y / 3;
      if (rnd(band, 0, salt + 4) > 0.55f && std::abs(u - rnd(band, 1, salt + 4)) < 0.18f) t.rgb = glm::vec3(0.15f);
      break;
    }
    case TextureId::kLogTop: {
      const float d = std::sqrt((u - 0.5f) * (u - 0.5f) + (v - 0.5f) * (v - 0.5f));
      const float ring = 0.5f + 0.5f * std::cos(d * 40.0f);
      t.rgb = glm::mix(rgb(150, 115, 70), rgb(185, 150, 95), ring) * (d > 0.44f ? 0.6f : 1.0f);
      break;
    }
    case TextureId::kOakLeaves: t = leaves(u, v, x, y, salt, rgb(40, 95, 30), rgb(80, 150, 55), 0.18f); break;
    case TextureId::kBirchLeaves: t = leaves(u, v, x, y, salt, rgb(85, 130, 40), rgb(150, 190, 70), 0.22f); break;
    case TextureId::kAcaciaLeaves: t = leaves(u, v, x, y, salt, rgb(95, 115, 35), rgb(150, 160, 60), 0.25f); break;
    case TextureId::kJungleLeaves: t = leaves(u, v, x, y, salt, rgb(25, 85, 25), rgb(60, 140, 40), 0.12f); break;
    case TextureId::kBushLeaves: t = leaves(u, v, x, y, salt, rgb(50, 105, 45), rgb(95, 150, 70), 0.2f); break;
    case TextureId::kBerryLeaves: {
      t = leaves(u, v, x, y, salt, rgb(45, 100, 50), rgb(90, 145, 65), 0.2f);
      if (t.alpha > 0.0f && rnd(x, y, salt + 7) > 0.93f) t.rgb = rgb(190, 30, 50);  // berries
      break;
    }
    case TextureId::kTallGrass:
    case TextureId::kFlowers: {
      // Blades rising from the bottom edge, each with its own height and lean.
      t.alpha = 0.0f;
      const int blades = 6;
      for (int b = 0; b < blades; ++b) {
        const float root = (static_cast<float>(b) + 0.5f) / blades + 0.08f * (rnd(b, 0, salt + 8) - 0.5f);
        const float height = 0.45f + 0.5f * rnd(b, 1, salt + 8);
        const float lean = 0.3f * (rnd(b, 2, salt + 8) - 0.5f);
        const float h = 1.0f - v;  // 0 at the bottom
        if (h > height) continue;
        const float cx = root + lean * h;
        if (std::abs(u - cx) < 0.045f * (1.0f - h / height) + 0.02f) {
          t.alpha = 1.0f;
          t.rgb = glm::mix(rgb(55, 120, 40), rgb(120, 185, 70), h / height);
          t.specular = 0.2f;
        }
      }
      if (id == TextureId::kFlowers) {
        for (int f = 0; f < 3; ++f) {
          const float fx = 0.2f + 0.3f * static_cast<float>(f), fy = 0.25f + 0.2f * rnd(f, 3, salt + 8);
          if ((u - fx) * (u - fx) + (v - fy) * (v - fy) < 0.006f) {
            t.alpha = 1.0f;
            t.rgb = f == 1 ? rgb(240, 220, 60) : rgb(225, 70, 90);
          }
        }
      }
      break;
    }
    case TextureId::kLantern: {
      const bool frame = x == 0 || y == 0 || x == size - 1 || y == size - 1 || x == size / 2;
      t.rgb = frame ? rgb(60, 50, 40) : glm::mix(rgb(255, 190, 90), rgb(255, 230, 160), n);
      t.specular = frame ? 0.7f : 0.0f;
      break;
    }
    case TextureId::kGlowstone:
      t.rgb = glm::mix(rgb(150, 200, 255), rgb(230, 245, 255), value_noise(u, v, 5, salt + 3));
      break;
    case TextureId::kCount: break;
  }
  return t;
}

}  // namespace

BlockTextureImages generate_block_texture(TextureId id, int size, std::uint64_t seed) {
  SYLVA_ASSERT(size >= 4 && size <= 1024, "texture size {} outside [4, 1024]", size);
  SYLVA_ASSERT(static_cast<int>(id) >= 0 && static_cast<int>(id) < kTextureCount, "texture id {}", static_cast<int>(id));
  BlockTextureImages out{Image(size, size, 4, PixelFormat::kU8), Image(size, size, 1, PixelFormat::kU8)};
  const std::uint32_t salt = hash_u32(static_cast<std::uint32_t>(id), static_cast<std::uint32_t>(seed),
                                      static_cast<std::uint32_t>(seed >> 32));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const Texel t = texel(id, x, y, size, salt);
      for (int c = 0; c < 3; ++c) out.diffuse.at(x, y, c) = std::clamp(t.rgb[c], 0.0f, 1.0f);
      out.diffuse.at(x, y, 3) = t.alpha;
      out.specular.at(x, y, 0) = std::clamp(t.specular, 0.0f, 1.0f);
    }
  }
  return out;
}

}  // namespace sylva::voxel
