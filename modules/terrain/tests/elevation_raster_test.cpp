// Elevation rasters as users have them (issue 15, first section): small georeferenced GeoTIFFs
// written here through GDAL (projected UTM and geographic EPSG:4326, Int16 and Float32, with
// nodata), read by core read_elevation: spacing in metres, heights, vertical units, nodata fill
// and refusal, overrides, and bad input (truncated, unknown format, all nodata, huge header).
#include <sylva/core/elevation_raster.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>

#include <support/geotiff_fixture.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace sylva {
namespace {

namespace fs = std::filesystem;

fs::path temp(const std::string& name) {
  // One folder per process: ctest runs the tests of this file in parallel processes.
  const fs::path dir = fs::temp_directory_path() / ("sylva_elevation_raster_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

using test::LogCapture;

// 100 + 3 i - 2 j (i east, j south): distinct, exact in Int16 and Float32.
test::GeoTiffSpec ramp(int columns, int rows) {
  test::GeoTiffSpec s;
  s.columns = columns;
  s.rows = rows;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) s.values.push_back(100.0 + 3.0 * i - 2.0 * j);
  return s;
}

TEST(ElevationRaster, ProjectedInt16TiledCompressedKeepsSpacingAndHeights) {
  auto spec = ramp(40, 24);
  spec.options = {"TILED=YES", "BLOCKXSIZE=16", "BLOCKYSIZE=16", "COMPRESS=DEFLATE"};
  const fs::path file = temp("utm_int16.tif");
  test::write_geotiff(file, spec);
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_TRUE(r->georeferenced);
  EXPECT_EQ(r->reader, "GDAL GTiff");
  EXPECT_NE(r->crs.find("UTM zone 32N"), std::string::npos) << r->crs;
  ASSERT_EQ(r->field.columns(), 40);
  ASSERT_EQ(r->field.rows(), 24);
  EXPECT_DOUBLE_EQ(r->field.spacing(), 30.0);
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 40; ++i) ASSERT_EQ(r->field.sample(i, j), 100.0f + 3.0f * i - 2.0f * j) << i << "," << j;
}

TEST(ElevationRaster, FeetAreConvertedBothWays) {
  // NAD83 / New York Long Island (ftUS): the grid is in US survey feet, the heights in feet.
  auto spec = ramp(8, 6);
  spec.type = GDT_Float32;
  spec.epsg = 2263;
  spec.left = 1000000.0;
  spec.top = 200000.0;
  spec.pixel_x = spec.pixel_y = 100.0;
  spec.unit = "ft";
  const fs::path file = temp("feet.tif");
  test::write_geotiff(file, spec);
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_NEAR(r->field.spacing(), 100.0 * 1200.0 / 3937.0, 1e-9);
  EXPECT_NEAR(r->field.sample(5, 3), (100.0 + 15.0 - 6.0) * 0.3048, 1e-4);
}

TEST(ElevationRaster, GeographicSpacingIsConvertedAtTheCentreLatitudeAndResampledSquare) {
  // 3 arc-second WGS 84 grid centred on 45 N: a degree of latitude there is 111132.95 m and one
  // of longitude 78846.81 m (ellipsoid tables), so samples are 65.706 m east-west by 92.611 m
  // north-south and are resampled to 65.706 m squares.
  auto spec = ramp(20, 12);
  spec.type = GDT_Float32;
  spec.epsg = 4326;
  spec.pixel_x = spec.pixel_y = 1.0 / 1200.0;
  spec.left = 7.0;
  spec.top = 45.0 + 6.0 / 1200.0;
  const fs::path file = temp("geographic.tif");
  test::write_geotiff(file, spec);
  LogCapture log;
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_NEAR(r->source_spacing_x, 78846.81 / 1200.0, 0.01);
  EXPECT_NEAR(r->source_spacing_z, 111132.95 / 1200.0, 0.01);
  EXPECT_NEAR(r->field.spacing(), r->source_spacing_x, 1e-9);
  EXPECT_EQ(r->field.columns(), 20);
  EXPECT_EQ(r->field.rows(), 17);  // 11 * 92.611 / 65.706 = 15.5 -> 16 steps
  EXPECT_TRUE(LogCapture::any(log.info, file.string(), "centre latitude 45.0000"));
  // The ramp is linear, so bilinear resampling keeps it: row r lies r * 65.706 / 92.611 rows down.
  const double rows_per_row = r->field.spacing() / r->source_spacing_z;
  for (int row = 0; row < r->field.rows(); ++row) {
    const double j = std::min(row * rows_per_row, 11.0);
    EXPECT_NEAR(r->field.sample(4, row), 100.0 + 12.0 - 2.0 * j, 1e-3) << row;
  }
}

TEST(ElevationRaster, NodataIsFilledFromTheNearestValidSamplesWithAWarning) {
  auto spec = ramp(16, 16);
  spec.nodata = -32768.0;
  for (int j = 5; j < 8; ++j)
    for (int i = 5; i < 8; ++i) spec.values[j * 16 + i] = -32768.0;
  spec.values[0] = -32768.0;
  const fs::path file = temp("nodata_int16.tif");
  test::write_geotiff(file, spec);
  LogCapture log;
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_EQ(r->nodata_filled, 10u);
  EXPECT_TRUE(LogCapture::any(log.warnings, file.string(), "filled 10 "));
  // Filled samples lie within the heights around them; valid ones are untouched.
  for (int j = 5; j < 8; ++j) {
    for (int i = 5; i < 8; ++i) {
      EXPECT_GE(r->field.sample(i, j), 100.0f + 3 * 4 - 2 * 8) << i << "," << j;
      EXPECT_LE(r->field.sample(i, j), 100.0f + 3 * 8 - 2 * 4) << i << "," << j;
    }
  }
  EXPECT_NEAR(r->field.sample(0, 0), 100.0f, 3.0f);
  EXPECT_EQ(r->field.sample(4, 4), 100.0f + 12.0f - 8.0f);
  EXPECT_GT(r->field.min_height(), 50.0f);  // no -32768 left

  ElevationReadOptions refuse;
  refuse.nodata = NodataPolicy::kRefuse;
  auto refused = read_elevation(file, refuse);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.error().message.find(file.string()), std::string::npos);
  EXPECT_NE(refused.error().message.find("10 of 256"), std::string::npos) << refused.error().message;
}

// Golden values: what the reader gave before it read the samples straight into the HeightField
// and seeded the nodata flood with the holes' borders only (issue 15, raster bake memory). Both
// changes are meant to keep every height bit for bit.
TEST(ElevationRaster, FilledHeightsAreUnchangedBitForBit) {
  auto spec = ramp(12, 10);
  spec.type = GDT_Float32;
  spec.nodata = -9999.0;
  std::vector<int> holes;
  for (int j = 3; j < 6; ++j)
    for (int i = 4; i < 8; ++i) holes.push_back(j * 12 + i);
  holes.push_back(0);
  holes.push_back(9 * 12 + 11);
  for (int k : holes) spec.values[static_cast<std::size_t>(k)] = -9999.0;
  spec.values[2 * 12 + 10] = std::numeric_limits<double>::quiet_NaN();
  holes.push_back(2 * 12 + 10);
  const fs::path file = temp("golden_fill.tif");
  test::write_geotiff(file, spec);
  ElevationReadOptions o;
  o.height_scale = 0.37;
  o.height_offset = 12.5;
  auto r = read_elevation(file, o);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  ASSERT_EQ(r->nodata_filled, holes.size());
  // In the order of `holes`, printed with %.9g (exact for floats) by the code before the change.
  const float golden[] = {51.7035828f, 52.8040466f, 53.9147987f, 55.0348015f, 50.956768f,  52.0532761f,
                          53.164341f,  54.2884941f, 50.2235641f, 51.3240166f, 52.4347725f, 53.5547867f,
                          49.7466812f, 54.8033295f, 59.1199989f};
  for (std::size_t h = 0; h < holes.size(); ++h) {
    EXPECT_EQ(r->field.samples()[static_cast<std::size_t>(holes[h])], golden[h]) << "sample " << holes[h];
  }
  for (int j = 0; j < 10; ++j) {
    for (int i = 0; i < 12; ++i) {
      if (std::find(holes.begin(), holes.end(), j * 12 + i) != holes.end()) continue;
      ASSERT_EQ(r->field.sample(i, j), static_cast<float>((100.0 + 3.0 * i - 2.0 * j) * 0.37 + 12.5)) << i << "," << j;
    }
  }
}

// The reader reads a row of blocks at a time into the HeightField (GDAL's cache dropped between
// rows): a south-up, east-to-west raster of 16-row tiles, 3 rows of them with a partial last
// one, comes out north-up and west-to-east with every sample in place and the nodata across
// the tile rows filled.
TEST(ElevationRaster, RowsOfBlocksOfAFlippedTiledRasterLandInPlace) {
  auto spec = ramp(40, 37);
  spec.type = GDT_Float32;
  spec.pixel_x = spec.pixel_y = -30.0;  // gt[1] < 0: east to west; gt[5] > 0: south up
  spec.nodata = -9999.0;
  spec.options = {"TILED=YES", "BLOCKXSIZE=16", "BLOCKYSIZE=16"};
  for (int j = 14; j < 18; ++j) spec.values[static_cast<std::size_t>(j) * 40 + 20] = -9999.0;
  const fs::path file = temp("flipped_tiles.tif");
  test::write_geotiff(file, spec);
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  ASSERT_EQ(r->field.columns(), 40);
  ASSERT_EQ(r->field.rows(), 37);
  EXPECT_EQ(r->nodata_filled, 4u);
  for (int j = 0; j < 37; ++j) {
    for (int i = 0; i < 40; ++i) {
      const int file_i = 39 - i, file_j = 36 - j;
      const float v = r->field.sample(i, j);
      if (file_i == 20 && file_j >= 14 && file_j < 18) {
        EXPECT_NEAR(v, 100.0f + 3.0f * file_i - 2.0f * file_j, 6.0f) << i << "," << j;
        continue;
      }
      ASSERT_EQ(v, 100.0f + 3.0f * file_i - 2.0f * file_j) << i << "," << j;
    }
  }
}

TEST(ElevationRaster, FillCarriesTheNearestValidHeightsIntoLargeHoles) {
  // West half 100 m, east half 300 m, a 20x20 hole across the edge: smoothing alone would leave
  // the hole's middle far from both; the flood gives each side its nearest height.
  constexpr int n = 40;
  std::vector<float> values(n * n);
  std::vector<std::uint8_t> valid(n * n, 1);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      values[j * n + i] = i < n / 2 ? 100.0f : 300.0f;
      if (i >= 10 && i < 30 && j >= 10 && j < 30) {
        values[j * n + i] = -9999.0f;
        valid[j * n + i] = 0;
      }
    }
  }
  const std::vector<float> before = values;
  EXPECT_EQ(fill_nodata(values, valid, n, n), 400u);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float v = values[j * n + i];
      if (valid[j * n + i]) {
        ASSERT_EQ(v, before[j * n + i]);
        continue;
      }
      ASSERT_GE(v, 100.0f) << i << "," << j;
      ASSERT_LE(v, 300.0f) << i << "," << j;
      if (i < 14) {
        EXPECT_LT(v, 130.0f) << i << "," << j;
      }
      if (i >= 26) {
        EXPECT_GT(v, 270.0f) << i << "," << j;
      }
    }
  }
}

TEST(ElevationRaster, FloatNaNCountsAsNodata) {
  auto spec = ramp(8, 8);
  spec.type = GDT_Float32;
  spec.values[9] = std::numeric_limits<double>::quiet_NaN();
  const fs::path file = temp("nan_float.tif");
  test::write_geotiff(file, spec);
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_EQ(r->nodata_filled, 1u);
  EXPECT_TRUE(std::isfinite(r->field.sample(1, 1)));
}

TEST(ElevationRaster, AllNodataIsAnErrorNamingTheFile) {
  auto spec = ramp(8, 8);
  spec.nodata = -9999.0;
  std::fill(spec.values.begin(), spec.values.end(), -9999.0);
  const fs::path file = temp("all_nodata.tif");
  test::write_geotiff(file, spec);
  auto r = read_elevation(file);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(r.error().message.find(file.string()), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("all 64 samples"), std::string::npos) << r.error().message;
}

TEST(ElevationRaster, OverridesWinOverTheFile) {
  auto spec = ramp(8, 6);
  spec.unit = "ft";  // ignored once height_scale is given
  const fs::path file = temp("overrides.tif");
  test::write_geotiff(file, spec);
  ElevationReadOptions o;
  o.spacing = 5.0;
  o.height_scale = 2.0;
  o.height_offset = 10.0;
  auto r = read_elevation(file, o);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_DOUBLE_EQ(r->field.spacing(), 5.0);
  EXPECT_EQ(r->field.sample(2, 1), (100.0f + 6.0f - 2.0f) * 2.0f + 10.0f);
}

TEST(ElevationRaster, AsciiGridWithoutCoordinateSystemIsReadInMetres) {
  const fs::path file = temp("grid.asc");
  std::ofstream(file) << "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 12.5\nNODATA_value -9999\n"
                         "1 2 3 4\n5 -9999 7 8\n9 10 11 12\n";
  LogCapture log;
  auto r = read_elevation(file);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_EQ(r->reader, "GDAL AAIGrid");
  EXPECT_DOUBLE_EQ(r->field.spacing(), 12.5);
  EXPECT_EQ(r->field.sample(3, 0), 4.0f);
  EXPECT_EQ(r->field.sample(0, 2), 9.0f);
  EXPECT_EQ(r->nodata_filled, 1u);
  EXPECT_TRUE(LogCapture::any(log.info, file.string(), "taken as metres"));
}

TEST(ElevationRaster, SrtmHgtTileIsReadAsGeographicMetres) {
  // A 3 arc-second SRTM tile (1201^2 Int16, nodata -32768) made by GDAL's own SRTMHGT writer.
  auto spec = ramp(1201, 1201);
  spec.epsg = 4326;
  spec.pixel_x = spec.pixel_y = 1.0 / 1200.0;
  spec.left = 7.0 - 0.5 / 1200.0;
  spec.top = 47.0 + 0.5 / 1200.0;
  spec.values[600 * 1201 + 600] = -32768.0;
  const fs::path tif = temp("srtm_source.tif");
  test::write_geotiff(tif, spec);
  const fs::path hgt = temp("N46E007.hgt");
  GDALDatasetH source = GDALOpen(tif.string().c_str(), GA_ReadOnly);
  ASSERT_NE(source, nullptr);
  GDALDatasetH copy = GDALCreateCopy(GDALGetDriverByName("SRTMHGT"), hgt.string().c_str(), source, FALSE, nullptr,
                                     nullptr, nullptr);
  ASSERT_NE(copy, nullptr) << CPLGetLastErrorMsg();
  GDALClose(copy);
  GDALClose(source);
  auto r = read_elevation(hgt);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_EQ(r->reader, "GDAL SRTMHGT");
  EXPECT_EQ(r->nodata_filled, 1u);  // SRTM's void value
  EXPECT_NEAR(r->source_spacing_z, 111141.0 / 1200.0, 0.5);  // 1 degree of latitude near 46.5 N
  EXPECT_NEAR(r->field.spacing(), r->source_spacing_x, 1e-9);
  EXPECT_LT(r->field.spacing(), r->source_spacing_z);
  EXPECT_EQ(r->field.sample(0, 0), 100.0f);
}

TEST(ElevationRaster, PictureWithoutGeoreferencingGoesThroughOpenImageIO) {
  Image img(11, 5, 1, PixelFormat::kU16);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 11; ++x) img.at(x, y) = static_cast<float>(x * 1000 + y) / 65535.0f;
  const fs::path file = temp("plain16.png");
  ASSERT_TRUE(write_image(file, img, PixelFormat::kU16).ok());
  ElevationReadOptions o;
  o.plain_extent = 100.0;
  o.height_scale = 65535.0;
  auto r = read_elevation(file, o);
  ASSERT_TRUE(r.ok()) << r.error().describe();
  EXPECT_FALSE(r->georeferenced);
  EXPECT_EQ(r->reader, "OpenImageIO");
  EXPECT_DOUBLE_EQ(r->field.spacing(), 10.0);
  EXPECT_NEAR(r->field.sample(7, 3), 7003.0f, 1e-2f);
}

TEST(ElevationRaster, TruncatedFileIsACorruptError) {
  auto spec = ramp(256, 256);
  const fs::path file = temp("truncated.tif");
  test::write_geotiff(file, spec);
  fs::resize_file(file, fs::file_size(file) / 3);
  auto r = read_elevation(file);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt) << r.error().describe();
  EXPECT_NE(r.error().message.find(file.string()), std::string::npos) << r.error().message;
}

TEST(ElevationRaster, UnknownFormatIsUnsupportedNamingTheFile) {
  const fs::path file = temp("mystery.dem");
  std::ofstream(file, std::ios::binary) << std::string("\x7f\x01\x02 not a raster of any kind \xff\xfe", 32);
  auto r = read_elevation(file);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kUnsupported) << r.error().describe();
  EXPECT_NE(r.error().message.find(file.string()), std::string::npos) << r.error().message;
}

TEST(ElevationRaster, HugeHeaderIsALimitBeforeAnythingIsAllocated) {
  // 40000^2 Int16 claimed by a sparse file of a few hundred kB: 6 GiB as floats.
  test::GeoTiffSpec spec;
  spec.columns = spec.rows = 40000;
  spec.write_values = false;
  spec.options = {"TILED=YES", "BLOCKXSIZE=512", "BLOCKYSIZE=512"};
  const fs::path file = temp("huge_header.tif");
  test::write_geotiff(file, spec);
  auto r = read_elevation(file);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kLimit);
  EXPECT_NE(r.error().message.find(file.string()), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("40000x40000"), std::string::npos) << r.error().message;
}

TEST(ElevationRaster, MissingFileIsNotFound) {
  auto r = read_elevation(temp("no_such.tif"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace sylva
