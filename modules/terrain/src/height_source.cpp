#include <sylva/terrain/height_source.hpp>

#include "parallel.hpp"

#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>

namespace sylva::terrain {

Result<HeightField> generate_height_field(const GeneratedFieldSettings& settings) {
  SYLVA_TRY(validate_params(settings, "terrain.field"));
  const int columns = settings.size;
  const int rows = settings.rows > 0 ? settings.rows : settings.size;
  HeightField field(columns, rows, settings.spacing);
  FbmSettings fbm = settings.fbm;
  // Lattice cells per sample: the first octave has one cell per feature_size metres.
  fbm.frequency = static_cast<float>(settings.spacing / static_cast<double>(settings.feature_size));
  const bool ridged = settings.noise == FieldNoise::kRidged;
  detail::parallel_for(static_cast<std::size_t>(rows), 0, [&](std::size_t j) {
    for (int i = 0; i < columns; ++i) {
      const glm::dvec2 p(static_cast<double>(i), static_cast<double>(j));
      // fbm2 is in [-1, 1], ridged2 in [0, 1]: both mapped to [0, 1].
      const float n = ridged ? ridged2(p, fbm) : 0.5f * (fbm2(p, fbm) + 1.0f);
      field.sample(i, static_cast<int>(j)) = settings.height_offset + settings.height_scale * n;
    }
  }, nullptr, 8);
  field.update_range();
  return field;
}

Result<HeightField> load_height_field(const std::filesystem::path& path, const HeightImageSettings& settings) {
  auto image = read_image(path);
  if (!image.ok()) return image.error();
  if (image->format() == PixelFormat::kU8) {
    log_warn("terrain: {} is an 8-bit image: only 256 height levels ({:.3f} m steps); use 16-bit PNG or float "
             "EXR/TIFF for terrain", path.string(), settings.height_scale / 255.0);
  }
  HeightFieldImageOptions options;
  options.spacing = settings.spacing;
  options.height_scale = settings.height_scale;
  options.height_offset = settings.height_offset;
  options.channel = settings.channel;
  options.non_finite = settings.repair_non_finite ? NonFinitePolicy::kRepair : NonFinitePolicy::kReject;
  auto field = HeightField::from_image(*image, options);
  if (!field.ok()) {
    return make_error(field.error().code, fmt::format("{}: {}", path.string(), field.error().message));
  }
  return field;
}

}  // namespace sylva::terrain
