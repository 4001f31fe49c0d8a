// HDR output (tone_mapping.hpp) and the time-of-day sun and sky (time_of_day.hpp): the GPU tone
// curve equals its CPU twin per pixel, NaN/negative/inf inputs give finite, sane outputs, both
// operators are monotonic; the sun rises and sets on the horizon, passes the zenith when asked,
// reddens near the horizon, is off at night, and the sky drawn from it and tone mapped has no
// NaN at noon, at the horizon and at night.
#include "support/render_test_support.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/time_of_day.hpp>
#include <sylva/render/tone_mapping.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::render {
namespace {

TEST(ToneCurves, MonotonicAndBounded) {
  float last_a = -1.0f, last_r = -1.0f;
  for (float x = 0.0f; x < 1000.0f; x = x * 1.2f + 0.001f) {
    const float a = tone_map_aces(x), r = tone_map_reinhard(x);
    EXPECT_GE(a, last_a);
    EXPECT_GE(r, last_r);
    EXPECT_LE(a, 1.0f);
    EXPECT_LT(r, 1.0f);
    last_a = a;
    last_r = r;
  }
  EXPECT_NEAR(tone_map_aces(0.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(linear_to_srgb_exact(0.5f), 0.7353569f, 1e-5f);
  ToneMapSettings s;
  EXPECT_EQ(tone_map_channel(std::numeric_limits<float>::quiet_NaN(), s), 0.0f);
  EXPECT_EQ(tone_map_channel(-5.0f, s), 0.0f);
  EXPECT_NEAR(tone_map_channel(std::numeric_limits<float>::infinity(), s), 1.0f, 1e-6f);
}

TEST(TimeOfDay, SunPathColourAndNight) {
  TimeOfDaySettings s;
  s.noon_elevation_deg = 60.0f;
  s.hours = 12.0f;
  EXPECT_NEAR(time_of_day_elevation(s), 60.0f * 3.14159265f / 180.0f, 1e-5f);
  const Lighting noon = lighting_for_time_of_day(s);
  EXPECT_GT(noon.sun_direction.z, 0.0f);  // due south (+z) at noon
  s.hours = 6.0f;
  EXPECT_NEAR(time_of_day_elevation(s), 0.0f, 1e-6f);
  const Lighting sunrise = lighting_for_time_of_day(s);
  EXPECT_NEAR(sunrise.sun_direction.y, 0.0f, 1e-5f);
  EXPECT_GT(sunrise.sun_direction.x, 0.99f);  // due east
  s.hours = 6.3f;
  const Lighting low = lighting_for_time_of_day(s);
  EXPECT_GT(low.sun_color.x / low.sun_color.z, 1.5f * noon.sun_color.x / noon.sun_color.z) << "reddens at the horizon";
  EXPECT_LT(low.sun_intensity, noon.sun_intensity);
  s.hours = 0.0f;
  const Lighting night = lighting_for_time_of_day(s);
  EXPECT_EQ(night.sun_intensity, 0.0f);
  EXPECT_LT(night.zenith_color.z, 0.05f);
  s.noon_elevation_deg = 90.0f;
  s.hours = 12.0f;
  const Lighting zenith = lighting_for_time_of_day(s);
  EXPECT_NEAR(zenith.sun_direction.y, 1.0f, 1e-6f);
  // The sky straight up is the zenith colour the lighting carries (one model).
  const glm::vec3 up = sky_radiance(zenith, {0.0f, 1.0f, 0.0f});
  EXPECT_NEAR(up.z, zenith.zenith_color.z, 1.0e-5f);
  for (float h = -30.0f; h <= 50.0f; h += 0.37f) {
    s.hours = h;
    const Lighting l = lighting_for_time_of_day(s);
    for (const glm::vec3& v : {l.sun_direction, l.sun_color, l.ambient, l.horizon_color, l.zenith_color, l.fog_color}) {
      ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << h;
    }
    ASSERT_TRUE(std::isfinite(l.sun_intensity));
    EXPECT_NEAR(glm::length(l.sun_direction), 1.0f, 1e-5f);
  }
}

using ToneMappingGl = GlTest;

TEST_F(ToneMappingGl, GpuMatchesCpuIncludingBadPixels) {
  constexpr int kW = 64, kH = 4;
  Image hdr(kW, kH, 4, PixelFormat::kF32);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 3; ++c) hdr.at(x, y, c) = 1e-3f * std::pow(1.25f, static_cast<float>(x + c * 3 + y * 7));
      hdr.at(x, y, 3) = 1.0f;
    }
  }
  hdr.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  hdr.at(1, 0, 1) = -3.0f;
  hdr.at(2, 0, 2) = std::numeric_limits<float>::infinity();
  TextureOptions opt;
  opt.encoding = TextureEncoding::kFloat32;
  opt.mipmaps = false;
  opt.min_filter = GL_NEAREST;
  opt.mag_filter = GL_NEAREST;
  Result<Texture> tex = Texture::from_image(hdr, opt);
  ASSERT_TRUE(tex.ok()) << tex.error().describe();
  Result<ToneMapper> tm = ToneMapper::create();
  ASSERT_TRUE(tm.ok()) << tm.error().describe();
  Framebuffer fb = test::make_target(kW, kH);
  for (const ToneOperator op : {ToneOperator::kAces, ToneOperator::kReinhard}) {
    ToneMapSettings s;
    s.tone_operator = op;
    s.exposure = 0.8f;
    fb.bind();
    fb.clear({1, 0, 1, 1});
    tm->apply(*tex, s);
    Result<Image> out = read_color(fb);
    ASSERT_TRUE(out.ok());
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        for (int c = 0; c < 3; ++c) {
          const float expected = tone_map_channel(hdr.at(x, y, c), s);
          ASSERT_NEAR(out->at(x, y, c), expected, 1.5f / 255.0f) << x << "," << y << " c" << c << " in " << hdr.at(x, y, c);
        }
      }
    }
  }
}

TEST_F(ToneMappingGl, TimeOfDaySkyHasNoNanAtNoonHorizonAndNight) {
  constexpr int kW = 96, kH = 48;
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok());
  Result<ToneMapper> tm = ToneMapper::create();
  ASSERT_TRUE(tm.ok());
  FramebufferDesc desc;
  desc.width = kW;
  desc.height = kH;
  desc.color_formats = {GL_RGBA16F};
  Result<Framebuffer> hdr = Framebuffer::create(desc);
  ASSERT_TRUE(hdr.ok());
  Framebuffer ldr = test::make_target(kW, kH);
  for (const float hours : {12.0f, 6.0f, 18.02f, 0.0f}) {
    TimeOfDaySettings s;
    s.hours = hours;
    s.noon_elevation_deg = 90.0f;  // noon is a zenith sun
    const Lighting lighting = lighting_for_time_of_day(s);
    Camera cam;
    cam.set_aspect(kW, kH);
    cam.look_at(cam.position() + glm::dvec3(lighting.sun_direction.x, 0.2, lighting.sun_direction.z + 1e-3));
    hdr->bind();
    hdr->clear({0, 0, 0, 1});
    sky->draw(cam, lighting);
    Result<Image> h = read_color(*hdr);
    ASSERT_TRUE(h.ok());
    ldr.bind();
    tm->apply(hdr->color_texture(), ToneMapSettings{});
    Result<Image> l = read_color(ldr);
    ASSERT_TRUE(l.ok());
    test::save_for_inspection(*l, "time_of_day_sky_" + std::to_string(static_cast<int>(hours * 100)));
    double sum = 0.0;
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(std::isfinite(h->at(x, y, c))) << hours << "h at " << x << "," << y;
          ASSERT_GE(h->at(x, y, c), 0.0f);
          sum += l->at(x, y, c);
        }
      }
    }
    const double mean = sum / (kW * kH * 3);
    if (hours == 12.0f) {
      EXPECT_GT(mean, 0.3) << "daylight sky";
    } else if (hours == 0.0f) {
      EXPECT_LT(mean, 0.15) << "night sky";
    }
  }
}

}  // namespace
}  // namespace sylva::render
