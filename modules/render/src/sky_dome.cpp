// The sky dome's mesh (sky_dome.hpp).
#include <sylva/render/sky_dome.hpp>

#include <sylva/render/atmosphere.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

constexpr float kHalfPi = 1.5707963f;

// Fills the gaps between consecutive sorted elevations evenly, at most max_step(gap's middle)
// apart.
template <class MaxStep>
std::vector<float> fill_gaps(const std::vector<float>& sorted, MaxStep max_step) {
  std::vector<float> out;
  for (std::size_t i = 0; i + 1 < sorted.size(); ++i) {
    const float a = sorted[i];
    const float b = sorted[i + 1];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a) / max_step(0.5f * (a + b)))));
    for (int k = 0; k < steps; ++k) out.push_back(a + (b - a) * static_cast<float>(k) / static_cast<float>(steps));
  }
  out.push_back(sorted.back());
  return out;
}

}  // namespace

std::vector<float> sky_dome_ring_elevations() {
  // Above the horizon: the table's rows cut into kRowSteps in row space (row = 15 sqrt(sin e)).
  std::vector<float> key;
  const int row_steps = (SkyTable::kRows - 1) * SkyDomeMesh::kRowSteps;
  for (int k = 0; k <= row_steps; ++k) {
    const float t = static_cast<float>(k) / static_cast<float>(row_steps);
    key.push_back(std::asin(t * t));
  }
  // Below: the horizon's haze is the same down a spoke, only the nadir's fade (30 degrees from
  // it) changes with elevation; fill_gaps spaces both evenly.
  const float fade_start = -std::acos(SkyTable::kNadirFade);
  key.push_back(fade_start);
  key.push_back(-kHalfPi);
  std::sort(key.begin(), key.end());
  std::vector<float> rings = fill_gaps(key, [fade_start](float e) {
    return e < fade_start ? SkyDomeMesh::kNadirRingStepRad : SkyDomeMesh::kMaxRingStepRad;
  });
  // The poles are single vertices, not rings.
  rings.erase(std::remove_if(rings.begin(), rings.end(), [](float e) { return std::abs(e) >= kHalfPi - 1.0e-6f; }),
              rings.end());
  return rings;
}

SkyDomeMesh build_sky_dome() {
  SkyDomeMesh mesh;
  const std::vector<float> rings = sky_dome_ring_elevations();
  const int spokes = SkyDomeMesh::kSpokes;
  for (const float e : rings) {
    for (int s = 0; s < spokes; ++s) {
      const float az = static_cast<float>(s) / static_cast<float>(spokes) * 6.2831853f;
      mesh.directions.emplace_back(std::cos(e) * std::cos(az), std::sin(e), std::cos(e) * std::sin(az));
    }
  }
  const auto nadir = static_cast<std::uint32_t>(mesh.directions.size());
  mesh.directions.emplace_back(0.0f, -1.0f, 0.0f);
  const auto zenith = static_cast<std::uint32_t>(mesh.directions.size());
  mesh.directions.emplace_back(0.0f, 1.0f, 0.0f);
  const auto at = [&](std::size_t ring, int s) { return static_cast<std::uint32_t>(ring * spokes + (s % spokes)); };
  const std::size_t top = rings.size() - 1;
  const float fade_start = -std::acos(SkyTable::kNadirFade);
  const auto cap_top = static_cast<std::size_t>(std::find(rings.begin(), rings.end(), fade_start) - rings.begin());
  const auto band = [&](std::size_t r, int s) {
    mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1)});
    mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s)});
  };
  // The nadir's cap first (fan and the bands up to the fade's ring), then the rest.
  for (int s = 0; s < spokes; ++s) {
    mesh.indices.insert(mesh.indices.end(), {nadir, at(0, s + 1), at(0, s)});
    for (std::size_t r = 0; r < cap_top; ++r) band(r, s);
  }
  mesh.nadir_cap_indices = mesh.indices.size();
  for (int s = 0; s < spokes; ++s) {
    for (std::size_t r = cap_top; r < top; ++r) band(r, s);
    mesh.indices.insert(mesh.indices.end(), {at(top, s), at(top, s + 1), zenith});
  }
  return mesh;
}

}  // namespace sylva::render
