#include <sylva/vegetation/textures.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/noise.hpp>
#include <sylva/core/rng.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::vegetation {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kPetiole = 0.1f;  // v range of the leaf stalk

bool power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

float smooth01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// Half width (in u) of the blade at blade parameter s in [0, 1] (0 = base of the blade).
float half_width(const LeafTextureSettings& st, float s) {
  if (s <= 0.0f || s >= 1.0f) return 0.0f;
  float w = 0.0f;
  switch (st.shape) {
    case LeafShape::kOvate:  // widest below the middle, pointed tip
      w = (0.47f / 0.3644f) * std::pow(s, 0.6f) * std::pow(1.0f - s, 0.9f);
      break;
    case LeafShape::kElliptic:  // widest in the middle, both ends pointed
      w = (0.40f / 0.3789f) * std::pow(s * (1.0f - s), 0.7f);
      break;
    case LeafShape::kBirch:
      w = (0.47f / 0.349f) * std::pow(s, 0.55f) * std::pow(1.0f - s, 1.1f);
      break;
    case LeafShape::kNeedles:
      return 0.0f;
  }
  if (st.serration > 0.0f) {
    const float teeth = s * 26.0f;
    const float saw = teeth - std::floor(teeth);  // sawtooth: teeth point to the tip
    w *= 1.0f - st.serration * 0.08f * saw;
  }
  return w;
}

// Distance from p to the segment a-b.
float segment_distance(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

float needle_coverage(float u, float v, float px) {
  const glm::vec2 p(u, v);
  // Twig along the centre, then needles alternating left and right, slanted to the tip.
  float d = segment_distance(p, {0.5f, 0.0f}, {0.5f, 0.93f}) - 0.012f;
  constexpr int kNeedles = 26;
  for (int k = 0; k < kNeedles; ++k) {
    const float v0 = 0.06f + 0.85f * static_cast<float>(k) / static_cast<float>(kNeedles - 1);
    const float side = (k % 2 == 0) ? 1.0f : -1.0f;
    const float len = 0.38f * (1.0f - 0.45f * v0);
    const glm::vec2 a(0.5f, v0);
    const glm::vec2 b(0.5f + side * len * 0.8f, std::min(v0 + len * 0.6f, 0.995f));
    const glm::vec2 ab = b - a;
    const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    const float half = 0.016f * (1.0f - 0.6f * t);
    d = std::min(d, glm::length(p - (a + t * ab)) - half);
  }
  return std::clamp(0.5f - d / px, 0.0f, 1.0f);
}

// Vein relief in [0, 1] (midrib and secondary veins), zero outside the blade.
struct Veins {
  float midrib = 0.0f;
  float secondary = 0.0f;
};

Veins veins_at(const LeafTextureSettings& st, float u, float v) {
  Veins out;
  const float x = u - 0.5f;
  if (st.shape == LeafShape::kNeedles) {
    out.midrib = std::exp(-(x * x) / (0.008f * 0.008f)) * (v < 0.93f ? 1.0f : 0.0f);
    return out;
  }
  const float mid_w = 0.011f * (1.0f - 0.6f * v);
  out.midrib = std::exp(-(x * x) / (mid_w * mid_w)) * (v < 0.97f ? 1.0f : 0.0f);
  if (v < kPetiole) return out;
  const float ax = std::fabs(x);
  const float angle = 0.9f;  // radians from the midrib
  const float sa = std::sin(angle);
  const float ca = std::cos(angle);
  const float t = ax / sa;  // distance along a vein reaching this |x|
  for (int k = 0; k < st.veins; ++k) {
    const float vk = kPetiole + (1.0f - kPetiole) * (static_cast<float>(k) + 0.6f) / (static_cast<float>(st.veins) + 0.6f);
    const float vv = vk + t * ca + 0.9f * t * t;  // veins curve towards the tip
    const float dist = std::fabs(v - vv) * sa;
    const float w = 0.0055f * (1.0f - std::min(t / 0.5f, 0.8f));
    out.secondary = std::max(out.secondary, 0.6f * std::exp(-(dist * dist) / (w * w)));
  }
  return out;
}

// Tileable gradient noise on the unit square at integer lattice frequency f.
float tile_noise(float u, float v, int f, std::uint32_t seed) {
  const float ff = static_cast<float>(f);
  const glm::vec2 p(u * ff, v * ff);
  const float a = gradient_noise2(p, seed);
  const float b = gradient_noise2(p - glm::vec2(ff, 0.0f), seed);
  const float c = gradient_noise2(p - glm::vec2(0.0f, ff), seed);
  const float d = gradient_noise2(p - glm::vec2(ff, ff), seed);
  return (a * (1.0f - u) + b * u) * (1.0f - v) + (c * (1.0f - u) + d * u) * v;
}

float tile_fbm(float u, float v, int f, int octaves, std::uint32_t seed) {
  float sum = 0.0f;
  float amp = 1.0f;
  float norm = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * tile_noise(u, v, f << o, hash_u32(static_cast<std::uint32_t>(o), seed));
    norm += amp;
    amp *= 0.5f;
  }
  return sum / norm;
}

// Normal map (tangent space, x = +u, y = +v) from a height image (1 channel, Image rows top-down).
// sign_x flips the x derivative (the lower side's tangent space has x = -u).
void normals_from_height(const Image& h, float strength, float sign_x, Image& out, bool wrap) {
  const int w = h.width();
  const int ht = h.height();
  for (int y = 0; y < ht; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto at = [&](int xx, int yy) {
        if (wrap) return h.at((xx + w) % w, (yy + ht) % ht);
        return h.at_clamped(xx, yy);
      };
      const float du = 0.5f * (at(x + 1, y) - at(x - 1, y));
      const float dv = -0.5f * (at(x, y + 1) - at(x, y - 1));  // image y grows downwards, v upwards
      const glm::vec3 n = glm::normalize(glm::vec3(-sign_x * strength * du, -strength * dv, 1.0f));
      out.at(x, y, 0) = 0.5f + 0.5f * n.x;
      out.at(x, y, 1) = 0.5f + 0.5f * n.y;
      out.at(x, y, 2) = 0.5f + 0.5f * n.z;
    }
  }
}

glm::vec3 decode_normal(const Image& img, int x, int y) {
  return glm::normalize(glm::vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)) * 2.0f - 1.0f);
}

// Eq. 3.28 projected on the HL2 lobes: h(x0) for light arriving on the side whose normal map is
// `lit_normal` (its tangent space) and passing to the other side. The kernel factors into a
// Gaussian of the distance times exp(-k d(x_i)) of the source texel, so the convolution runs as
// two 1D Gaussian passes over exp(-k d) g(n(x_i)) (plain float loops: this runs per texture).
void translucency_coefficients(const LeafTextureSettings& st, const Image& lit_normal, const Image& thickness_src,
                               const Image& coverage, Image& out) {
  const int size = lit_normal.width();
  const auto n_px = static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
  constexpr int kDirections = 64;
  const std::array<glm::vec3, 3> H = hl2_basis();
  const float k = std::sqrt(3.0f / (2.0f * kPi));
  float dirs[kDirections][3];
  float basis[kDirections][3];
  for (int i = 0; i < kDirections; ++i) {
    const float z = 1.0f - (static_cast<float>(i) + 0.5f) / static_cast<float>(kDirections);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = static_cast<float>(i) * 2.39996323f;
    const glm::vec3 L(r * std::cos(phi), r * std::sin(phi), z);
    for (int c = 0; c < 3; ++c) {
      dirs[i][c] = L[c];
      basis[i][c] = k * glm::dot(H[static_cast<std::size_t>(c)], L);
    }
  }
  glm::dmat3 gram(0.0);
  for (int i = 0; i < kDirections; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) gram[a][b] += static_cast<double>(basis[i][a]) * static_cast<double>(basis[i][b]);
  const glm::dmat3 gram_inv = glm::inverse(gram);
  // Source term per texel and lobe: coverage * exp(-k d) * sum_L max(n . L, 0) basis(L).
  std::vector<float> src[3];
  for (auto& v : src) v.assign(n_px, 0.0f);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const glm::vec3 n = decode_normal(lit_normal, x, y);
      float acc[3] = {0.0f, 0.0f, 0.0f};
      for (int i = 0; i < kDirections; ++i) {
        const float e = std::max(n.x * dirs[i][0] + n.y * dirs[i][1] + n.z * dirs[i][2], 0.0f);
        acc[0] += e * basis[i][0];
        acc[1] += e * basis[i][1];
        acc[2] += e * basis[i][2];
      }
      const float w = coverage.at(x, y) * std::exp(-st.thickness_absorption * thickness_src.at(x, y));
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
      for (int c = 0; c < 3; ++c) src[c][p] = acc[c] * w;
    }
  }
  // Normalised 1D Gaussian; clamped borders as the 2D kernel had.
  const float sigma = st.scattering_radius;
  const int radius = static_cast<int>(std::ceil(2.0f * sigma));
  std::vector<float> g1;
  float norm = 0.0f;
  for (int d = -radius; d <= radius; ++d) {
    g1.push_back(std::exp(-static_cast<float>(d * d) / (2.0f * sigma * sigma)));
    norm += g1.back();
  }
  for (float& v : g1) v /= norm;
  std::vector<float> tmp(n_px);
  for (int c = 0; c < 3; ++c) {
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        float acc = 0.0f;
        for (int d = -radius; d <= radius; ++d) {
          const int xx = std::clamp(x + d, 0, size - 1);
          acc += g1[static_cast<std::size_t>(d + radius)] * src[c][static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(xx)];
        }
        tmp[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] = acc;
      }
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        float acc = 0.0f;
        for (int d = -radius; d <= radius; ++d) {
          const int yy = std::clamp(y + d, 0, size - 1);
          acc += g1[static_cast<std::size_t>(d + radius)] * tmp[static_cast<std::size_t>(yy) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)];
        }
        src[c][static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] = acc;
      }
  }
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
      const glm::dvec3 h = gram_inv * glm::dvec3(src[0][p], src[1][p], src[2][p]);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = std::clamp(0.5f + 0.5f * static_cast<float>(h[c]), 0.0f, 1.0f);
    }
  }
}

// Coverage of one leaf (or needle spray) filling the unit square, anti-aliased over `px`.
float single_coverage(const LeafTextureSettings& st, float u, float v, float px) {
  if (st.shape == LeafShape::kNeedles) return needle_coverage(u, v, px);
  const float x = std::fabs(u - 0.5f);
  // Stalk.
  float d = (v <= kPetiole + 0.02f) ? x - 0.016f : 1.0f;
  if (v < 0.0f) d = 1.0f;
  // Blade.
  const float s = (v - kPetiole) / (1.0f - kPetiole - 0.01f);
  if (s > 0.0f && s < 1.0f) d = std::min(d, x - half_width(st, s));
  return std::clamp(0.5f - d / px, 0.0f, 1.0f);
}

// One leaf of a cluster card: base point, unit axis (base to tip) and length in card units.
struct ClusterLeaf {
  glm::vec2 base{0.5f, 0.0f};
  glm::vec2 axis{0.0f, 1.0f};
  float length = 1.0f;
};

// Twig along u = 0.5 with the leaves alternating at 50-60 degrees and a terminal leaf; leaf size
// chosen so that the leaves together cover about 60 % of the card (sqrt(area / count)).
std::vector<ClusterLeaf> cluster_layout(const LeafTextureSettings& st) {
  const int k = std::max(1, st.cluster);
  if (k == 1) return {ClusterLeaf{}};
  const float area = st.shape == LeafShape::kNeedles ? 2.2f : 1.25f;
  const float len = std::min(st.shape == LeafShape::kNeedles ? 0.62f : 0.52f, std::sqrt(area / static_cast<float>(k)));
  std::vector<ClusterLeaf> out;
  const float v_top = 0.99f - len;
  const int sides = k - 1;
  for (int i = 0; i < sides; ++i) {
    const float r = hash_to_unit_float(hash_u32(static_cast<std::uint32_t>(i), st.seed, 91u));
    const float v0 = 0.03f + (v_top - 0.06f) * static_cast<float>(i) / static_cast<float>(std::max(1, sides - 1));
    const float side = (i % 2 == 0) ? 1.0f : -1.0f;
    const float angle = (52.0f + 12.0f * r) * kPi / 180.0f;
    const float l = len * (0.85f + 0.25f * static_cast<float>(i + 1) / static_cast<float>(sides));
    out.push_back({{0.5f, v0}, {side * std::sin(angle), std::cos(angle)}, l});
  }
  out.push_back({{0.5f, v_top}, {0.0f, 1.0f}, len});
  return out;
}

}  // namespace

ClusterSample cluster_sample(const LeafTextureSettings& st, float u, float v) {
  const float px = 1.0f / static_cast<float>(st.size);
  ClusterSample best;
  best.u = u;
  best.v = v;
  if (std::max(1, st.cluster) == 1) {
    best.coverage = single_coverage(st, u, v, px);
    best.leaf = 0;
    return best;
  }
  const std::vector<ClusterLeaf> leaves = cluster_layout(st);
  // The twig: from the card's base to the terminal leaf.
  const float twig_d = segment_distance({u, v}, {0.5f, 0.0f}, leaves.back().base) - 0.009f;
  best.coverage = std::clamp(0.5f - twig_d / px, 0.0f, 1.0f);
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const ClusterLeaf& l = leaves[i];
    const glm::vec2 q = glm::vec2(u, v) - l.base;
    const glm::vec2 across(l.axis.y, -l.axis.x);
    const float lu = 0.5f + glm::dot(q, across) / l.length;
    const float lv = glm::dot(q, l.axis) / l.length;
    const float c = single_coverage(st, lu, lv, px / l.length);
    // Later leaves (nearer the tip) lie over earlier ones.
    if (c > 0.0f && (c > 0.5f || c > best.coverage)) {
      best.coverage = std::max(best.coverage, c);
      best.u = lu;
      best.v = lv;
      best.leaf = static_cast<int>(i);
    }
  }
  return best;
}

namespace {

// Colour deviation of one leaf of a cluster (older leaves darker, some yellower), or the twig's
// bark brown (leaf = -1), so that a card reads as several leaves.
glm::vec3 cluster_tint(const LeafTextureSettings& st, int leaf) {
  if (leaf < 0) return {0.06f, -0.12f, 0.0f};
  const float b = 2.0f * hash_to_unit_float(hash_u32(static_cast<std::uint32_t>(leaf), st.seed, 92u)) - 1.0f;
  const float y = 2.0f * hash_to_unit_float(hash_u32(static_cast<std::uint32_t>(leaf), st.seed, 93u)) - 1.0f;
  return 1.6f * st.color_variation * glm::vec3(0.5f * b + 0.6f * y, b + 0.3f * y, 0.3f * b);
}

// Each leaf of a cluster turns about its midrib (a random tilt up to +-34 degrees plus a cupped
// cross-section of +-17 degrees at the edges), so the card's normals vary as a real spray's leaves do and it shades unevenly
// under the sun instead of as one flat plane.
void tilt_cluster_leaves(const LeafTextureSettings& st, const std::vector<int>& leaf_of, const std::vector<float>& across,
                         LeafTextures& out) {
  const std::vector<ClusterLeaf> layout = cluster_layout(st);
  const int n = st.size;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x);
      const int k = leaf_of[p];
      if (k < 0) continue;
      const ClusterLeaf& l = layout[static_cast<std::size_t>(k)];
      const float r = 2.0f * hash_to_unit_float(hash_u32(static_cast<std::uint32_t>(k), st.seed, 94u)) - 1.0f;
      const float angle = 0.6f * r + 0.6f * across[p];
      const glm::vec3 axis(l.axis.x, l.axis.y, 0.0f);
      const auto rotate = [&](glm::vec3 v) {  // Rodrigues, axis in the card plane
        return v * std::cos(angle) + glm::cross(axis, v) * std::sin(angle) + axis * glm::dot(axis, v) * (1.0f - std::cos(angle));
      };
      const glm::vec3 f = rotate(decode_normal(out.front.normal, x, y));
      // The lower side's tangent space has x = -u and z = -n: rotate in card space, map back.
      glm::vec3 b = decode_normal(out.back.normal, x, y);
      b = rotate(glm::vec3(-b.x, b.y, -b.z));
      b = glm::vec3(-b.x, b.y, -b.z);
      for (int c = 0; c < 3; ++c) {
        out.front.normal.at(x, y, c) = 0.5f + 0.5f * f[c];
        out.back.normal.at(x, y, c) = 0.5f + 0.5f * b[c];
      }
    }
}

Status check(bool ok, const char* path, const std::string& what) {
  if (ok) return ok_status();
  return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", path, what));
}

}  // namespace

std::array<glm::vec3, 3> hl2_basis() {
  const float s6 = 1.0f / std::sqrt(6.0f);
  const float s2 = 1.0f / std::sqrt(2.0f);
  const float s3 = 1.0f / std::sqrt(3.0f);
  return {glm::vec3(-s6, -s2, s3), glm::vec3(-s6, s2, s3), glm::vec3(std::sqrt(2.0f / 3.0f), 0.0f, s3)};
}

float hl2_reconstruct(const glm::vec3& h, float rho, const glm::vec3& L) {
  const std::array<glm::vec3, 3> H = hl2_basis();
  const float k = std::sqrt(3.0f / (2.0f * kPi));
  const float sum = h.x * k * glm::dot(H[0], L) + h.y * k * glm::dot(H[1], L) + h.z * k * glm::dot(H[2], L);
  return rho * std::max(sum, 0.0f);
}

float mean_leaf_transmittance(const LeafTextures& t) {
  const Image& col = t.front.color;
  const Image& tr = t.front.translucency;
  double sum = 0.0;
  double n = 0.0;
  for (int y = 0; y < col.height(); ++y)
    for (int x = 0; x < col.width(); ++x) {
      if (col.at(x, y, 3) <= 0.5f) continue;
      const glm::vec3 h = glm::vec3(tr.at(x, y, 0), tr.at(x, y, 1), tr.at(x, y, 2)) * 2.0f - 1.0f;
      sum += hl2_reconstruct(h, tr.at(x, y, 3), {0.0f, 0.0f, 1.0f});
      n += 1.0;
    }
  return n > 0.0 ? static_cast<float>(sum / n) : 0.0f;
}

LeafTextureSettings leaf_texture_settings_for(LeafShape shape, std::uint32_t seed) {
  LeafTextureSettings s;
  s.shape = shape;
  s.seed = seed;
  switch (shape) {
    // Cluster sizes: a broadleaf twig carries about five leaves, birch and shrub sprays more and
    // smaller ones, a conifer branchlet three needle sprays (compare SpeedTree / ez-tree cards).
    case LeafShape::kOvate: s.veins = 7; s.cluster = 5; break;
    case LeafShape::kElliptic: s.veins = 6; s.translucency = 0.5f; s.cluster = 7; break;
    case LeafShape::kBirch: s.veins = 6; s.serration = 0.8f; s.translucency = 0.7f; s.cluster = 7; break;
    case LeafShape::kNeedles: s.veins = 0; s.translucency = 0.3f; s.color_variation = 0.04f; s.cluster = 3; break;
  }
  return s;
}

float leaf_coverage(const LeafTextureSettings& st, float u, float v) { return cluster_sample(st, u, v).coverage; }

Result<LeafTextures> generate_leaf_textures(const LeafTextureSettings& st) {
  SYLVA_TRY(validate_params(st, "leaf_texture"));
  SYLVA_TRY(check(power_of_two(st.size), "leaf_texture.size", fmt::format("{} is not a power of two", st.size)));
  const int n = st.size;
  Image coverage(n, n, 1);
  Image height(n, n, 1);   // vein relief
  Image thickness(n, n, 1);
  Image mid(n, n, 1);
  std::vector<int> leaf_of(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), -1);
  std::vector<float> across_of(leaf_of.size(), 0.0f);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
      const float v = 1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
      const ClusterSample cs = cluster_sample(st, u, v);
      const float a = cs.coverage;
      const Veins vn = cs.leaf >= 0 ? veins_at(st, cs.u, cs.v) : Veins{};
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x);
      leaf_of[p] = a > 0.0f ? cs.leaf : -1;
      across_of[p] = cs.u - 0.5f;
      const float relief = std::max(vn.midrib, vn.secondary) + 0.04f * gradient_noise2(glm::vec2(u, v) * 40.0f, st.seed);
      coverage.at(x, y) = a;
      height.at(x, y) = a > 0.0f ? relief * a : 0.0f;
      mid.at(x, y) = vn.midrib;
      thickness.at(x, y) = a > 0.0f ? std::clamp(0.25f + 0.5f * vn.midrib + 0.25f * vn.secondary, 0.0f, 1.0f) : 0.0f;
    }
  }
  LeafTextures out;
  for (LeafSide* side : {&out.front, &out.back}) {
    side->color = Image(n, n, 4, PixelFormat::kU8);
    side->normal = Image(n, n, 4, PixelFormat::kU8);
    side->translucency = Image(n, n, 4, PixelFormat::kU8);
  }
  // Upper side: veins are grooves; lower side: ribs, seen in the mirrored tangent space.
  Image relief_front(n, n, 1);
  Image relief_back(n, n, 1);
  const float strength = 6.0f * st.vein_depth;
  for (std::size_t i = 0; i < height.data().size(); ++i) {
    relief_front.data()[i] = -height.data()[i];
    relief_back.data()[i] = height.data()[i];
  }
  normals_from_height(relief_front, strength, 1.0f, out.front.normal, false);
  normals_from_height(relief_back, strength, -1.0f, out.back.normal, false);
  if (st.cluster > 1) tilt_cluster_leaves(st, leaf_of, across_of, out);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
      const float v = 1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
      const float a = coverage.at(x, y);
      const float h = height.at(x, y);
      const float f1 = fbm2(glm::vec2(u, v) * 5.0f, FbmSettings{.octaves = 4, .seed = st.seed});
      const float f2 = fbm2(glm::vec2(u, v) * 7.0f, FbmSettings{.octaves = 3, .seed = st.seed + 17u});
      // Deviation c_v: mottling, lighter veins, a paler lower side.
      glm::vec3 front = st.color_variation * glm::vec3(0.7f * f1 + 0.3f * f2, f1, 0.4f * f1) +
                        glm::vec3(0.05f, 0.06f, 0.0f) * h;
      glm::vec3 back = st.color_variation * glm::vec3(0.6f * f2, 0.8f * f2, 0.5f * f2) +
                       st.back_lightness * glm::vec3(1.0f, 0.9f, 1.1f) + glm::vec3(0.06f, 0.06f, 0.02f) * h;
      if (st.cluster > 1) {
        const glm::vec3 tint = cluster_tint(st, leaf_of[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)]);
        front += tint;
        back += tint;
      }
      for (int c = 0; c < 3; ++c) {
        out.front.color.at(x, y, c) = std::clamp(0.5f + front[c], 0.0f, 1.0f);
        out.back.color.at(x, y, c) = std::clamp(0.5f + back[c], 0.0f, 1.0f);
      }
      out.front.color.at(x, y, 3) = a;
      out.back.color.at(x, y, 3) = a;
      out.front.normal.at(x, y, 3) = thickness.at(x, y);
      out.back.normal.at(x, y, 3) = thickness.at(x, y);
      const float rho = a > 0.0f ? st.translucency * (1.0f - 0.5f * smooth01(h)) : 0.0f;
      out.front.translucency.at(x, y, 3) = rho;
      out.back.translucency.at(x, y, 3) = rho;
    }
  }
  // Viewing the upper side with the light behind: light enters through the lower side.
  translucency_coefficients(st, out.back.normal, thickness, coverage, out.front.translucency);
  translucency_coefficients(st, out.front.normal, thickness, coverage, out.back.translucency);
  return out;
}

BarkTextureSettings bark_texture_settings_for(SpeciesPreset preset, std::uint32_t seed) {
  BarkTextureSettings s;
  s.seed = seed;
  switch (preset) {
    case SpeciesPreset::kBroadleaf: break;
    case SpeciesPreset::kConifer:
      s.color = {0.30f, 0.19f, 0.13f};
      s.furrow_color = {0.09f, 0.06f, 0.045f};
      s.furrows = 12;
      s.roughness = 0.7f;
      break;
    case SpeciesPreset::kBirch:
      s.color = {0.78f, 0.76f, 0.72f};
      s.furrow_color = {0.08f, 0.07f, 0.06f};
      s.furrows = 5;
      s.furrow_depth = 0.3f;
      s.horizontal_marks = 0.8f;
      break;
    case SpeciesPreset::kShrub:
      s.color = {0.35f, 0.28f, 0.2f};
      s.furrows = 6;
      s.furrow_depth = 0.5f;
      break;
  }
  return s;
}

Result<BarkTextures> generate_bark_textures(const BarkTextureSettings& st) {
  SYLVA_TRY(validate_params(st, "bark_texture"));
  SYLVA_TRY(check(power_of_two(st.size), "bark_texture.size", fmt::format("{} is not a power of two", st.size)));
  const int n = st.size;
  Image height(n, n, 1);
  BarkTextures out{Image(n, n, 4, PixelFormat::kU8), Image(n, n, 4, PixelFormat::kU8)};
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const float u = static_cast<float>(x) / static_cast<float>(n);
      const float v = 1.0f - static_cast<float>(y) / static_cast<float>(n);
      const float wobble = 0.35f * tile_fbm(u, v, 3, 3, st.seed);
      const float phase = u * static_cast<float>(st.furrows) + wobble;
      float plates = std::pow(std::fabs(std::sin(kPi * phase)), 0.6f);
      // Plates break along the branch.
      const float breaks = tile_noise(u, v, 8, st.seed + 5u);
      plates *= 0.75f + 0.25f * smooth01(0.5f + 2.0f * breaks);
      const float fine = tile_fbm(u, v, 16, 3, st.seed + 9u);
      float h = (1.0f - st.roughness * 0.4f) * plates + st.roughness * 0.4f * (0.5f + 0.5f * fine);
      float mark = 0.0f;
      if (st.horizontal_marks > 0.0f) {
        const float m = tile_noise(u, v * 1.0f, 12, st.seed + 21u) + 0.5f * tile_noise(u, v, 24, st.seed + 22u);
        mark = st.horizontal_marks * smooth01((m - 0.25f) * 6.0f);
        h = h * (1.0f - 0.6f * mark);
      }
      height.at(x, y) = h;
      const float shade = 1.0f + 0.15f * fine;
      const glm::vec3 c = glm::mix(st.furrow_color, st.color, smooth01(h)) * shade;
      const glm::vec3 col = glm::mix(c, st.furrow_color, mark);
      for (int ch = 0; ch < 3; ++ch) out.albedo.at(x, y, ch) = std::clamp(col[ch], 0.0f, 1.0f);
      out.albedo.at(x, y, 3) = 1.0f;
      out.normal.at(x, y, 3) = std::clamp(h, 0.0f, 1.0f);
    }
  }
  normals_from_height(height, 8.0f * st.furrow_depth, 1.0f, out.normal, true);
  return out;
}

Image resample_image(const Image& src, int width, int height, bool alpha_weighted) {
  SYLVA_ASSERT(!src.empty() && width > 0 && height > 0, "{}x{} -> {}x{}", src.width(), src.height(), width, height);
  const int channels = src.channels();
  const bool weighted = alpha_weighted && channels == 4;
  Image out(width, height, channels, src.format());
  const float sx = static_cast<float>(src.width()) / static_cast<float>(width);
  const float sy = static_cast<float>(src.height()) / static_cast<float>(height);
  // Taps per axis: one bilinear tap per source texel of the footprint when shrinking.
  const int kx = std::max(1, static_cast<int>(std::ceil(sx)));
  const int ky = std::max(1, static_cast<int>(std::ceil(sy)));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float plain[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      float by_alpha[3] = {0.0f, 0.0f, 0.0f};
      float alpha_sum = 0.0f;
      for (int j = 0; j < ky; ++j)
        for (int i = 0; i < kx; ++i) {
          const float fx = (static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(kx)) * sx - 0.5f;
          const float fy = (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(ky)) * sy - 0.5f;
          const int x0 = static_cast<int>(std::floor(fx));
          const int y0 = static_cast<int>(std::floor(fy));
          const float tx = fx - static_cast<float>(x0);
          const float ty = fy - static_cast<float>(y0);
          const float wt[4] = {(1.0f - tx) * (1.0f - ty), tx * (1.0f - ty), (1.0f - tx) * ty, tx * ty};
          const int px[4] = {x0, x0 + 1, x0, x0 + 1};
          const int py[4] = {y0, y0, y0 + 1, y0 + 1};
          for (int k = 0; k < 4; ++k) {
            const float alpha = weighted ? src.at_clamped(px[k], py[k], 3) : 0.0f;
            for (int c = 0; c < channels; ++c) {
              const float v = src.at_clamped(px[k], py[k], c);
              plain[c] += wt[k] * v;
              if (weighted && c < 3) by_alpha[c] += wt[k] * alpha * v;
            }
            alpha_sum += wt[k] * alpha;
          }
        }
      const float taps = static_cast<float>(kx * ky);
      for (int c = 0; c < channels; ++c)
        out.at(x, y, c) = weighted && c < 3 && alpha_sum > 0.0f ? by_alpha[c] / alpha_sum : plain[c] / taps;
    }
  return out;
}

Result<LeafImageTextures> leaf_textures_from_images(const LeafImages& in, const LeafTextureSettings& st) {
  SYLVA_TRY(validate_params(st, "leaf_texture"));
  SYLVA_TRY(check(power_of_two(st.size), "leaf_texture.size", fmt::format("{} is not a power of two", st.size)));
  if (in.color.empty() || in.color.channels() != 4)
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("leaf images: the colour image must be RGBA (alpha = the outline), found {} channels", in.color.channels()));
  const int n = st.size;
  const Image color = resample_image(in.color, n, n, true);
  // The leaf's base colour: the mean over the covered texels (seed §3.2, Fig. 3.15 c).
  glm::dvec3 sum(0.0);
  double covered = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (color.at(x, y, 3) <= 0.5f) continue;
      sum += glm::dvec3(color.at(x, y, 0), color.at(x, y, 1), color.at(x, y, 2));
      covered += 1.0;
    }
  if (covered == 0.0)
    return make_error(ErrorCode::kInvalidArgument, "leaf images: no texel of the colour image has alpha above 0.5 (the leaf outline is empty)");
  LeafImageTextures result;
  result.base_color = glm::vec3(sum / covered);
  LeafTextures& out = result.textures;
  for (LeafSide* side : {&out.front, &out.back}) {
    side->color = Image(n, n, 4, PixelFormat::kU8);
    side->normal = Image(n, n, 4, PixelFormat::kU8);
    side->translucency = Image(n, n, 4, PixelFormat::kU8);
  }
  const Image normal = in.normal.empty() ? Image() : resample_image(in.normal, n, n);
  const Image trans = in.translucency.empty() ? Image() : resample_image(in.translucency, n, n);
  Image coverage(n, n, 1);
  Image thickness(n, n, 1);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float a = color.at(x, y, 3);
      coverage.at(x, y) = a;
      glm::vec3 nf(0.0f, 0.0f, 1.0f);
      float d = 0.25f;
      if (!normal.empty()) {
        const glm::vec3 raw = glm::vec3(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)) * 2.0f - 1.0f;
        if (glm::length(raw) > 1e-4f) nf = glm::normalize(raw);
        if (normal.channels() == 4) d = std::clamp(normal.at(x, y, 3), 0.0f, 1.0f);
      }
      thickness.at(x, y) = a > 0.0f ? d : 0.0f;
      // The lower side's tangent space is (-u, v, -n): the same surface seen from below.
      const glm::vec3 nb(nf.x, -nf.y, nf.z);
      float rho = st.translucency;
      if (!trans.empty()) {
        rho = trans.channels() >= 3 ? (trans.at(x, y, 0) + trans.at(x, y, 1) + trans.at(x, y, 2)) / 3.0f : trans.at(x, y, 0);
      }
      rho = a > 0.0f ? std::clamp(rho, 0.0f, 1.0f) : 0.0f;
      for (LeafSide* side : {&out.front, &out.back}) {
        const glm::vec3& ns = side == &out.front ? nf : nb;
        for (int c = 0; c < 3; ++c) {
          side->color.at(x, y, c) = std::clamp(0.5f + color.at(x, y, c) - result.base_color[c], 0.0f, 1.0f);
          side->normal.at(x, y, c) = 0.5f + 0.5f * ns[c];
        }
        side->color.at(x, y, 3) = a;
        side->normal.at(x, y, 3) = thickness.at(x, y);
        side->translucency.at(x, y, 3) = rho;
      }
    }
  translucency_coefficients(st, out.back.normal, thickness, coverage, out.front.translucency);
  translucency_coefficients(st, out.front.normal, thickness, coverage, out.back.translucency);
  return result;
}

Result<BarkTextures> bark_textures_from_images(const Image& color, const Image& normal, int size) {
  SYLVA_TRY(check(power_of_two(size), "bark_texture.size", fmt::format("{} is not a power of two", size)));
  if (color.empty() || color.channels() < 3)
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("bark images: the colour image must be RGB or RGBA, found {} channels", color.channels()));
  const int n = size;
  const Image albedo = resample_image(color, n, n);
  const Image nr = normal.empty() ? Image() : resample_image(normal, n, n);
  BarkTextures out{Image(n, n, 4, PixelFormat::kU8), Image(n, n, 4, PixelFormat::kU8)};
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      glm::vec3 nv(0.0f, 0.0f, 1.0f);
      float h = 0.5f;
      if (!nr.empty()) {
        const glm::vec3 raw = glm::vec3(nr.at(x, y, 0), nr.at(x, y, 1), nr.at(x, y, 2)) * 2.0f - 1.0f;
        if (glm::length(raw) > 1e-4f) nv = glm::normalize(raw);
        if (nr.channels() == 4) h = std::clamp(nr.at(x, y, 3), 0.0f, 1.0f);
      }
      for (int c = 0; c < 3; ++c) {
        out.albedo.at(x, y, c) = std::clamp(albedo.at(x, y, c), 0.0f, 1.0f);
        out.normal.at(x, y, c) = 0.5f + 0.5f * nv[c];
      }
      out.albedo.at(x, y, 3) = 1.0f;
      out.normal.at(x, y, 3) = h;
    }
  return out;
}

std::vector<SeasonKey> season_keys(SeasonPalette palette) {
  switch (palette) {
    case SeasonPalette::kDeciduous:
      return {{0.00f, {0.30f, 0.22f, 0.10f, 0.0f}}, {0.26f, {0.32f, 0.40f, 0.08f, 0.0f}},
              {0.31f, {0.30f, 0.50f, 0.10f, 1.0f}}, {0.38f, {0.18f, 0.38f, 0.07f, 1.0f}},
              {0.48f, {0.09f, 0.25f, 0.05f, 1.0f}}, {0.66f, {0.10f, 0.24f, 0.04f, 1.0f}},
              {0.73f, {0.45f, 0.40f, 0.06f, 1.0f}}, {0.78f, {0.60f, 0.22f, 0.04f, 1.0f}},
              {0.83f, {0.40f, 0.16f, 0.05f, 1.0f}}, {0.88f, {0.30f, 0.17f, 0.08f, 0.0f}}};
    case SeasonPalette::kBirch:
      return {{0.00f, {0.30f, 0.25f, 0.10f, 0.0f}}, {0.27f, {0.35f, 0.45f, 0.10f, 0.0f}},
              {0.32f, {0.32f, 0.55f, 0.12f, 1.0f}}, {0.45f, {0.14f, 0.32f, 0.06f, 1.0f}},
              {0.65f, {0.15f, 0.32f, 0.05f, 1.0f}}, {0.73f, {0.60f, 0.52f, 0.06f, 1.0f}},
              {0.80f, {0.62f, 0.42f, 0.05f, 1.0f}}, {0.84f, {0.45f, 0.30f, 0.06f, 1.0f}},
              {0.88f, {0.35f, 0.25f, 0.08f, 0.0f}}};
    case SeasonPalette::kEvergreen:
      // Spruce and fir needles are dark (linear albedo about 0.04-0.12 in green), lighter with the
      // fresh shoots of early summer.
      return {{0.00f, {0.035f, 0.085f, 0.04f, 1.0f}}, {0.35f, {0.07f, 0.16f, 0.05f, 1.0f}},
              {0.55f, {0.045f, 0.12f, 0.04f, 1.0f}}, {0.85f, {0.035f, 0.09f, 0.04f, 1.0f}}};
  }
  return {};
}

SeasonPalette season_palette_for(SpeciesPreset preset) {
  switch (preset) {
    case SpeciesPreset::kConifer: return SeasonPalette::kEvergreen;
    case SpeciesPreset::kBirch: return SeasonPalette::kBirch;
    default: return SeasonPalette::kDeciduous;
  }
}

namespace {

glm::vec4 interpolate_keys(const std::vector<SeasonKey>& keys, float coord) {
  const float c = coord - std::floor(coord);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const SeasonKey& a = keys[i];
    const SeasonKey& b = keys[(i + 1) % keys.size()];
    const float b_at = i + 1 < keys.size() ? b.at : b.at + 1.0f;
    const float cc = c < a.at ? c + 1.0f : c;
    if (cc >= a.at && cc <= b_at) {
      const float t = b_at > a.at ? (cc - a.at) / (b_at - a.at) : 0.0f;
      return glm::mix(a.color, b.color, t);
    }
  }
  return keys.front().color;
}

}  // namespace

Image generate_season_texture(SeasonPalette palette, int rows) {
  SYLVA_ASSERT(rows >= 2, "rows={}", rows);
  const std::vector<SeasonKey> keys = season_keys(palette);
  Image img(1, rows, 4, PixelFormat::kU8);
  for (int i = 0; i < rows; ++i) {
    const int j = rows - 1 - i;  // GL texel index from the bottom
    const float v = (static_cast<float>(j) + 0.5f) / static_cast<float>(rows);
    const glm::vec4 c = interpolate_keys(keys, v);
    for (int ch = 0; ch < 4; ++ch) img.at(0, i, ch) = c[ch];
  }
  return img;
}

glm::vec4 sample_season(const Image& tex, float coord) {
  const int rows = tex.height();
  const float v = coord - std::floor(coord);
  const float y = v * static_cast<float>(rows) - 0.5f;
  const float fl = std::floor(y);
  const float f = y - fl;
  const int j0 = ((static_cast<int>(fl) % rows) + rows) % rows;
  const int j1 = (j0 + 1) % rows;
  glm::vec4 a;
  glm::vec4 b;
  for (int ch = 0; ch < 4; ++ch) {
    a[ch] = tex.at(0, rows - 1 - j0, std::min(ch, tex.channels() - 1));
    b[ch] = tex.at(0, rows - 1 - j1, std::min(ch, tex.channels() - 1));
  }
  return glm::mix(a, b, f);
}

double alpha_coverage(const Image& rgba, float threshold) {
  SYLVA_ASSERT(rgba.channels() == 4, "channels={}", rgba.channels());
  std::size_t covered = 0;
  for (int y = 0; y < rgba.height(); ++y)
    for (int x = 0; x < rgba.width(); ++x) covered += rgba.at(x, y, 3) > threshold ? 1u : 0u;
  return static_cast<double>(covered) / static_cast<double>(rgba.pixel_count());
}

std::vector<Image> box_mips(const Image& rgba) {
  SYLVA_ASSERT(rgba.channels() == 4 && power_of_two(rgba.width()) && power_of_two(rgba.height()),
               "box_mips needs RGBA with power-of-two sides, got {}x{}x{}", rgba.width(), rgba.height(), rgba.channels());
  std::vector<Image> levels{rgba};
  while (levels.back().width() > 1 || levels.back().height() > 1) {
    const Image& src = levels.back();
    const int w = std::max(1, src.width() / 2);
    const int h = std::max(1, src.height() / 2);
    Image dst(w, h, 4, rgba.format());
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        glm::vec3 col(0.0f);
        glm::vec3 plain(0.0f);
        float alpha = 0.0f;
        int count = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = std::min(2 * x + dx, src.width() - 1);
            const int sy = std::min(2 * y + dy, src.height() - 1);
            const float a = src.at(sx, sy, 3);
            const glm::vec3 c(src.at(sx, sy, 0), src.at(sx, sy, 1), src.at(sx, sy, 2));
            col += a * c;
            plain += c;
            alpha += a;
            ++count;
          }
        const glm::vec3 c = alpha > 0.0f ? col / alpha : plain / static_cast<float>(count);
        for (int ch = 0; ch < 3; ++ch) dst.at(x, y, ch) = c[ch];
        dst.at(x, y, 3) = alpha / static_cast<float>(count);
      }
    }
    levels.push_back(std::move(dst));
  }
  return levels;
}

std::vector<Image> coverage_preserving_mips(const Image& rgba, float threshold) {
  std::vector<Image> levels = box_mips(rgba);
  const double target = alpha_coverage(rgba, threshold);
  for (std::size_t l = 1; l < levels.size(); ++l) {
    Image& img = levels[l];
    const auto coverage_at = [&](float scale) {
      std::size_t covered = 0;
      for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) covered += std::min(img.at(x, y, 3) * scale, 1.0f) > threshold ? 1u : 0u;
      return static_cast<double>(covered) / static_cast<double>(img.pixel_count());
    };
    float lo = 0.0f;
    float hi = 16.0f;
    for (int it = 0; it < 24; ++it) {
      const float mid = 0.5f * (lo + hi);
      (coverage_at(mid) < target ? lo : hi) = mid;
    }
    // Of the two bracketing scales take the one whose coverage is closer to the target.
    const float scale = std::fabs(coverage_at(lo) - target) < std::fabs(coverage_at(hi) - target) ? lo : hi;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) img.at(x, y, 3) = std::min(img.at(x, y, 3) * scale, 1.0f);
  }
  return levels;
}

namespace {

constexpr const char* kSideNames[2] = {"front", "back"};
constexpr const char* kMapNames[3] = {"color", "normal", "translucency"};

std::filesystem::path leaf_file(const std::filesystem::path& folder, const std::string& prefix, int side, int map) {
  return folder / fmt::format("{}_{}_{}.png", prefix, kSideNames[side], kMapNames[map]);
}

template <class Textures>
auto& leaf_map(Textures& t, int side, int map) {
  auto& s = side == 0 ? t.front : t.back;
  return map == 0 ? s.color : map == 1 ? s.normal : s.translucency;
}

Result<Image> load_rgba(const std::filesystem::path& path, int expected_size) {
  Result<Image> img = read_image(path);
  if (!img.ok()) return img.error();
  if (img->channels() != 4)
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: expected 4 channels, found {}", path.string(), img->channels()));
  if (expected_size > 0 && (img->width() != expected_size || img->height() != expected_size))
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: size {}x{} differs from the first map's {}x{}", path.string(),
                                                               img->width(), img->height(), expected_size, expected_size));
  if (img->width() != img->height() || !power_of_two(img->width()))
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: textures must be square with a power-of-two side, found {}x{}", path.string(),
                                  img->width(), img->height()));
  return img;
}

}  // namespace

Status save_leaf_textures(const std::filesystem::path& folder, const std::string& prefix, const LeafTextures& textures) {
  for (int side = 0; side < 2; ++side)
    for (int map = 0; map < 3; ++map)
      SYLVA_TRY(write_image(leaf_file(folder, prefix, side, map), leaf_map(textures, side, map), PixelFormat::kU8));
  return ok_status();
}

Result<LeafTextures> load_leaf_textures(const std::filesystem::path& folder, const std::string& prefix) {
  LeafTextures t;
  int size = 0;
  for (int side = 0; side < 2; ++side) {
    for (int map = 0; map < 3; ++map) {
      Result<Image> img = load_rgba(leaf_file(folder, prefix, side, map), size);
      if (!img.ok()) return img.error();
      size = img->width();
      leaf_map(t, side, map) = std::move(img).value();
    }
  }
  return t;
}

Status save_bark_textures(const std::filesystem::path& folder, const std::string& prefix, const BarkTextures& textures) {
  SYLVA_TRY(write_image(folder / (prefix + "_albedo.png"), textures.albedo, PixelFormat::kU8));
  return write_image(folder / (prefix + "_normal.png"), textures.normal, PixelFormat::kU8);
}

Result<BarkTextures> load_bark_textures(const std::filesystem::path& folder, const std::string& prefix) {
  Result<Image> albedo = load_rgba(folder / (prefix + "_albedo.png"), 0);
  if (!albedo.ok()) return albedo.error();
  Result<Image> normal = load_rgba(folder / (prefix + "_normal.png"), albedo->width());
  if (!normal.ok()) return normal.error();
  return BarkTextures{std::move(albedo).value(), std::move(normal).value()};
}

}  // namespace sylva::vegetation
