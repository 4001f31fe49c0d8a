#pragma once
// Sun and sky from one time-of-day parameter (issue 7): the sun follows a simple daily arc
// (rises due east at 6 h, highest at noon due south when `noon_elevation` < 90 deg, sets due
// west at 18 h, below the horizon at night), its colour is white sunlight attenuated by
// Rayleigh-like extinction along the air mass (Kasten & Young 1989), so it reddens at the
// horizon, and the ambient, sky and fog colours are derived from the atmosphere lit by the
// same sun (derive_sky_lighting, sky.hpp) so the sky, the lighting and the fog always agree.
// GL-free; the result is a render::Lighting ready for LightingUniforms and SkyRenderer.
// Colours are linear HDR RGB: tone map them (tone_mapping.hpp) before display.

#include <sylva/core/params.hpp>
#include <sylva/render/lighting.hpp>

namespace sylva::render {

struct TimeOfDaySettings {
  float hours = 10.0f;            // local solar time [h], 12 = noon
  float noon_elevation_deg = 60.0f;  // sun elevation at noon [deg]; 90 = passes the zenith
  float sun_intensity = 3.0f;     // multiplier at the zenith
  float turbidity = 1.0f;         // scales the extinction (1 = clear air)

  template <class V>
  void visit(V& v) {
    v(hours, "hours", {.min = 0.0, .max = 24.0, .unit = "h", .help = "Local solar time, 12 = noon"});
    v(noon_elevation_deg, "noon_elevation_deg", {.min = 0.0, .max = 90.0, .unit = "deg", .help = "Sun elevation at noon"});
    v(sun_intensity, "sun_intensity", {.min = 0.0, .max = 100.0, .help = "Sun brightness at the zenith"});
    v(turbidity, "turbidity", {.min = 0.1, .max = 10.0, .help = "Haze: scales atmospheric extinction"});
  }
};

// Sun elevation [rad] for the settings (negative at night).
float time_of_day_elevation(const TimeOfDaySettings& s);

// Relative optical air mass for an elevation [rad] (1 at the zenith, ~38 at the horizon,
// finite and capped below it).
float air_mass(float elevation);

// Lighting for the time of day: sun direction (unit, toward the sun, may point below the
// horizon at night: then sun_intensity is 0), colours, ambient, sky gradient, fog colour.
// `base` supplies the fields time of day does not set (fog density and falloff).
Lighting lighting_for_time_of_day(const TimeOfDaySettings& s, const Lighting& base = {});

}  // namespace sylva::render
