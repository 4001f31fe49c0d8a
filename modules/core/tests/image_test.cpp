// core images: formats, channels, round trips through OpenImageIO, and bad files.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/file_fault.hpp>
#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sys/mount.h>
#include <unistd.h>

namespace fs = std::filesystem;
using sylva::ErrorCode;
using sylva::FileFaultPoint;
using sylva::Image;
using sylva::PixelFormat;
using sylva::ScopedFileFault;

namespace {

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / ("sylva_image_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

Image gradient(int w, int h, int channels) {
  Image image(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y, c) = static_cast<float>((x * 7 + y * 13 + c * 29) % 256) / 255.f;
  return image;
}

}  // namespace

TEST(Image, CreateRejectsEmptyAndTooManyChannels) {
  EXPECT_EQ(Image::create(0, 0, 1).error().code, ErrorCode::kLimit);
  EXPECT_EQ(Image::create(4, 4, 5).error().code, ErrorCode::kUnsupported);
  EXPECT_TRUE(Image::create(3, 2, 4).ok());
}

TEST(Image, AccessIsRowMajorTopFirst) {
  Image image(3, 2, 2);
  image.at(2, 1, 1) = 0.5f;
  EXPECT_EQ(image.data()[(1 * 3 + 2) * 2 + 1], 0.5f);
  EXPECT_EQ(image.at_clamped(10, 10, 1), 0.5f);
  EXPECT_EQ(image.channel(1).at(2, 1), 0.5f);
}

using RoundTripCase = std::tuple<const char*, PixelFormat, int>;

std::string round_trip_name(const ::testing::TestParamInfo<RoundTripCase>& info) {
  const char* ext = std::get<0>(info.param);
  return std::string(ext + 1) + "_format" + std::to_string(static_cast<int>(std::get<1>(info.param))) + "_c" +
         std::to_string(std::get<2>(info.param));
}

class ImageRoundTrip : public ::testing::TestWithParam<std::tuple<const char*, PixelFormat, int>> {};

TEST_P(ImageRoundTrip, PreservesPixelsWithinFormatPrecision) {
  const auto [ext, format, channels] = GetParam();
  const fs::path path = temp_dir() / (std::string("rt_") + std::to_string(static_cast<int>(format)) + "_" +
                                      std::to_string(channels) + ext);
  const Image original = gradient(17, 9, channels);
  ASSERT_TRUE(sylva::write_image(path, original, format).ok());
  auto back = sylva::read_image(path);
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_EQ(back->width(), 17);
  ASSERT_EQ(back->height(), 9);
  ASSERT_EQ(back->channels(), channels);
  EXPECT_EQ(back->format(), format);
  const float tolerance = format == PixelFormat::kF32 ? 0.f : format == PixelFormat::kF16 ? 1e-3f : 0.5f / 255.f;
  for (std::size_t i = 0; i < original.data().size(); ++i) {
    ASSERT_NEAR(back->data()[i], original.data()[i], tolerance) << "element " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, ImageRoundTrip,
                         ::testing::Values(std::make_tuple(".png", PixelFormat::kU8, 1),
                                           std::make_tuple(".png", PixelFormat::kU8, 3),
                                           std::make_tuple(".png", PixelFormat::kU8, 4),
                                           std::make_tuple(".png", PixelFormat::kU16, 1),
                                           std::make_tuple(".png", PixelFormat::kU16, 2),
                                           std::make_tuple(".exr", PixelFormat::kF16, 3),
                                           std::make_tuple(".exr", PixelFormat::kF32, 1),
                                           std::make_tuple(".tif", PixelFormat::kF32, 4),
                                           std::make_tuple(".tif", PixelFormat::kU16, 1)),
                         round_trip_name);

TEST(Image, SixteenBitKeepsEveryLevel) {
  Image image(256, 256, 1, PixelFormat::kU16);
  for (int i = 0; i < 65536; ++i) image.data()[static_cast<std::size_t>(i)] = static_cast<float>(i) / 65535.f;
  const fs::path path = temp_dir() / "levels16.png";
  ASSERT_TRUE(sylva::write_image(path, image).ok());
  auto back = sylva::read_image(path);
  ASSERT_TRUE(back.ok());
  for (int i = 0; i < 65536; ++i) {
    ASSERT_EQ(std::lround(back->data()[static_cast<std::size_t>(i)] * 65535.f), i);
  }
}

TEST(Image, MissingFileIsNotFoundAndNamesThePath) {
  auto r = sylva::read_image("/nonexistent/dir/height.png");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
  EXPECT_NE(r.error().message.find("/nonexistent/dir/height.png"), std::string::npos);
}

TEST(Image, TruncatedPngIsCorrupt) {
  const fs::path full = temp_dir() / "full.png";
  ASSERT_TRUE(sylva::write_image(full, gradient(64, 64, 3), PixelFormat::kU8).ok());
  std::ifstream in(full, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const fs::path cut = temp_dir() / "cut.png";
  std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  auto r = sylva::read_image(cut);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find("cut.png"), std::string::npos);
}

// libtiff zero-fills strips that the file is too short for, and OpenImageIO reports success:
// the reader must still fail (the hostile suite's TiffStripShorterThanHeader).
TEST(Image, TiffStripShorterThanItsHeaderIsCorrupt) {
  std::string tiff = {'I', 'I', 42, 0, 8, 0, 0, 0, 8, 0};  // little-endian, first directory at 8, 8 entries
  auto entry = [&tiff](std::uint16_t tag, std::uint16_t type, std::uint32_t value) {
    const std::uint32_t count = 1;
    tiff.append(reinterpret_cast<const char*>(&tag), 2).append(reinterpret_cast<const char*>(&type), 2);
    tiff.append(reinterpret_cast<const char*>(&count), 4).append(reinterpret_cast<const char*>(&value), 4);
  };
  const std::uint32_t strip_at = 10 + 8 * 12 + 4;
  for (std::uint16_t tag : {256, 257}) entry(tag, 4, 512);  // 512 x 512 pixels
  entry(258, 3, 8);         // 8 bits
  entry(259, 3, 1);         // uncompressed
  entry(262, 3, 1);         // grey
  entry(273, 4, strip_at);  // one strip ...
  entry(278, 4, 512);
  entry(279, 4, 16);        // ... of 16 bytes instead of 262144
  tiff.append(4, '\0').append(16, '\x40');
  const fs::path file = temp_dir() / "short_strip.tif";
  std::ofstream(file, std::ios::binary).write(tiff.data(), static_cast<std::streamsize>(tiff.size()));
  auto r = sylva::read_image(file);
  ASSERT_FALSE(r.ok()) << "a 16-byte strip read as a 512x512 picture";
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find("short_strip.tif: truncated or corrupt image data"), std::string::npos)
      << r.error().message;
  EXPECT_LT(r.error().message.size(), 400u) << "one line per damaged strip is not a message";
}

TEST(Image, GarbageFileIsRejected) {
  const fs::path junk = temp_dir() / "junk.png";
  std::ofstream(junk) << "this is not an image";
  auto r = sylva::read_image(junk);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("junk.png"), std::string::npos);
}

TEST(Image, AbsurdlyLargeIsRefusedBeforeReading) {
  const fs::path path = temp_dir() / "wide.png";
  ASSERT_TRUE(sylva::write_image(path, Image(300, 2, 1, PixelFormat::kU8)).ok());
  auto r = sylva::read_image(path, {.max_side = 256});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kLimit);
  EXPECT_NE(r.error().message.find("300x2"), std::string::npos);
}

TEST(Image, MoreBytesThanTheBudgetIsRefusedBeforeReading) {
  const fs::path path = temp_dir() / "rgba.png";
  ASSERT_TRUE(sylva::write_image(path, Image(64, 32, 4, PixelFormat::kU8)).ok());
  auto r = sylva::read_image(path, {.max_bytes = 64 * 32 * 4 * 4 - 1});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kLimit);
  EXPECT_NE(r.error().message.find("64x32 with 4 channels"), std::string::npos) << r.error().message;
  EXPECT_TRUE(sylva::read_image(path, {.max_bytes = 64 * 32 * 4 * 4}).ok());
}

TEST(Image, NanInExrIsReportedWithPosition) {
  Image image(8, 4, 1, PixelFormat::kF32);
  image.at(5, 2) = std::numeric_limits<float>::quiet_NaN();
  image.at(6, 3) = std::numeric_limits<float>::infinity();
  const fs::path path = temp_dir() / "nan.exr";
  ASSERT_TRUE(sylva::write_image(path, image).ok());
  EXPECT_TRUE(sylva::read_image(path).ok());
  auto r = sylva::read_image(path, {.allow_non_finite = false});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("2 NaN/Inf"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("(5, 2)"), std::string::npos) << r.error().message;
}

std::string bytes_of(const fs::path& path) { return sylva::read_file(path).value_or("<unreadable>"); }

// No temporary file of a failed write is left in `dir`.
void expect_no_temporaries(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

// The old file is put at risk: a new image for the same path fails half way (disk full) or at the
// rename; the old bytes must survive.
TEST(Image, FailedWriteKeepsTheOldFile) {
  const fs::path path = temp_dir() / "keep.png";
  ASSERT_TRUE(sylva::write_image(path, gradient(16, 16, 3), PixelFormat::kU8).ok());
  const std::string before = bytes_of(path);
  for (const FileFaultPoint point : {FileFaultPoint::kWrite, FileFaultPoint::kRename}) {
    {
      ScopedFileFault fault([&](const fs::path& target, FileFaultPoint p) { return p == point && target == path; });
      auto written = sylva::write_image(path, gradient(64, 32, 3), PixelFormat::kU8);
      ASSERT_FALSE(written.ok());
      EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
    }
    EXPECT_EQ(bytes_of(path), before) << "fault at " << static_cast<int>(point);
    expect_no_temporaries(temp_dir());
  }
  // An empty image cannot be written; the old file must be untouched.
  EXPECT_FALSE(sylva::write_image(path, Image()).ok());
  // An unknown extension has no writer; nothing may be created or replaced.
  EXPECT_FALSE(sylva::write_image(temp_dir() / "x.unknownext", gradient(4, 4, 1)).ok());
  EXPECT_FALSE(fs::exists(temp_dir() / "x.unknownext"));
  EXPECT_EQ(bytes_of(path), before);
  expect_no_temporaries(temp_dir());
}

// A real full disk: a 64 KiB tmpfs holding the old file, and a new image too large for it at the
// same path. Needs permission to mount (root in CI); skipped otherwise.
TEST(Image, FullDiskKeepsTheOldFile) {
  const fs::path dir = temp_dir() / "small_disk";
  fs::create_directories(dir);
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=64k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
  }
  struct Unmount {
    fs::path dir;
    ~Unmount() { ::umount2(dir.c_str(), MNT_DETACH); }
  } unmount{dir};
  const fs::path path = dir / "keep.exr";
  ASSERT_TRUE(sylva::write_image(path, gradient(16, 16, 3), PixelFormat::kF32).ok());
  const std::string before = bytes_of(path);
  Image noise(256, 256, 4);  // 1 MiB of floats that no compression brings under 64 KiB
  std::uint32_t h = 1u;
  for (float& v : noise.data()) v = static_cast<float>((h = h * 1664525u + 1013904223u) >> 8) / 16777216.0f;
  auto written = sylva::write_image(path, noise, PixelFormat::kF32);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
  EXPECT_EQ(bytes_of(path), before);
  const sylva::Status text = sylva::write_file_atomic(path, std::string(200000, 'x'));
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(bytes_of(path), before);
  expect_no_temporaries(dir);
}

// The writer fails on the temporary file beside the target; the message must still name the
// user's path only (/proc refuses new files even to root).
TEST(Image, WriteIntoAFolderThatRefusesFilesNamesTheUsersPath) {
  auto s = sylva::write_image("/proc/sylva_image_test.png", gradient(4, 4, 3), PixelFormat::kU8);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().message.rfind("/proc/sylva_image_test.png: cannot create the file", 0), 0u) << s.error().message;
  EXPECT_EQ(s.error().message.find(".tmp"), std::string::npos) << s.error().message;
}

TEST(Image, WriteIntoMissingFolderFailsCleanly) {
  auto r = sylva::write_image("/nonexistent/folder/out.png", gradient(4, 4, 3));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kIo);
  EXPECT_NE(r.error().message.find("/nonexistent/folder/out.png"), std::string::npos);
}

// OpenEXR trusts the sizes in its header (exr_header_check.hpp): a hostile header must be refused
// by Sylva's walk before the library allocates what it declares.
namespace {

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

void put_le32(std::string& bytes, std::size_t at, std::int32_t value) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((static_cast<std::uint32_t>(value) >> (8 * i)) & 0xffu);
}

// A valid EXR's bytes and the offset just past the named attribute's type (its size field).
std::pair<std::string, std::size_t> exr_with_attribute(const fs::path& path, const std::string& attribute) {
  EXPECT_TRUE(sylva::write_image(path, gradient(8, 4, 1), PixelFormat::kF32).ok());
  std::string bytes = read_bytes(path);
  const std::size_t name = bytes.find(attribute + '\0');
  EXPECT_NE(name, std::string::npos) << attribute;
  const std::size_t type_end = bytes.find('\0', name + attribute.size() + 1);
  return {bytes, type_end + 1};
}

}  // namespace

TEST(Image, ExrAttributeLargerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
  const fs::path path = temp_dir() / "hostile_attribute.exr";
  auto [bytes, size_at] = exr_with_attribute(path, "channels");
  put_le32(bytes, size_at, 0x70000000);  // 1.8 GB in a file of a few hundred bytes
  write_bytes(path, bytes);
  auto r = sylva::read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find("hostile_attribute.exr: OpenEXR attribute \"channels\" declares 1879048192 bytes"),
            std::string::npos)
      << r.error().message;
}

TEST(Image, ExrDataWindowAboveTheLimitIsRefusedBeforeOpenExrSizesItsOffsetTable) {
  const fs::path path = temp_dir() / "hostile_window.exr";
  auto [bytes, size_at] = exr_with_attribute(path, "dataWindow");
  put_le32(bytes, size_at + 4 + 12, 1 << 30);  // ymax: a billion scan lines
  write_bytes(path, bytes);
  auto r = sylva::read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kLimit);
  EXPECT_NE(r.error().message.find("image is 8x1073741825, larger than the limit of 32768"), std::string::npos)
      << r.error().message;
  // Within the side limit but with more chunks than the file could index.
  put_le32(bytes, size_at + 4 + 12, 30000);
  write_bytes(path, bytes);
  r = sylva::read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("chunks but the file has only"), std::string::npos) << r.error().message;
}

TEST(Image, ExrFixedSizeAttributeDeclaringAnotherSizeIsRefused) {
  // OpenEXR reads a compression value as one byte whatever the header declares: a header saying
  // otherwise would be read out of step with Sylva's walk, so it is refused.
  const fs::path path = temp_dir() / "out_of_step.exr";
  auto [bytes, size_at] = exr_with_attribute(path, "compression");
  put_le32(bytes, size_at, 2);
  write_bytes(path, bytes);
  auto r = sylva::read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find("attribute \"compression\" of type compression declares 2 bytes instead of 1"),
            std::string::npos)
      << r.error().message;
}

TEST(Image, HeaderClaimingFarMorePixelsThanTheFileCanHoldIsRefusedBeforeAllocating) {
  // A 20-byte PGM claiming 20000 x 20000 samples (1.5 GiB as floats, under the byte budget).
  const fs::path path = temp_dir() / "bomb.pgm";
  write_bytes(path, std::string("P5\n20000 20000\n255\n") + std::string(4, '\x80'));
  auto r = sylva::read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find("bomb.pgm: header claims 20000x20000 with 1 channels"), std::string::npos)
      << r.error().message;
}

TEST(Image, ExrChannelListLongerThanDeclaredIsRefused) {
  // OpenEXR reads a channel list up to its empty name whatever size the header declares: a list
  // one byte longer than declared would put the library out of step with Sylva's walk.
  const fs::path path = temp_dir() / "long_channels.exr";
  auto [bytes, size_at] = exr_with_attribute(path, "channels");
  std::int32_t declared = 0;
  std::memcpy(&declared, bytes.data() + size_at, 4);
  put_le32(bytes, size_at, declared - 1);
  write_bytes(path, bytes);
  auto r = sylva::read_image(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kCorrupt);
  EXPECT_NE(r.error().message.find("channel list \"channels\" does not fill its"), std::string::npos) << r.error().message;
}
