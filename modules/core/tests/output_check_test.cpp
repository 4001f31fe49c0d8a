// Output checks made before any work: each names the path as given and the reason, never a
// temporary file, and leaves nothing behind.
#include <sylva/core/output_check.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace sylva {
namespace {

namespace fs = std::filesystem;

class OutputCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sylva_output_check_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "folder");
    std::ofstream(dir_ / "file.json") << "{}";
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Everything in the test folder, so a check that leaves its probe behind is caught.
  std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {})); }
  fs::path dir_;
};

void expect_error(const Status& s, ErrorCode code, const std::string& path, const std::string& why) {
  ASSERT_FALSE(s.ok()) << path;
  EXPECT_EQ(s.error().code, code);
  EXPECT_EQ(s.error().message.rfind(path + ": ", 0), 0u) << s.error().message;
  EXPECT_NE(s.error().message.find(why), std::string::npos) << s.error().message;
  EXPECT_EQ(s.error().message.find(".tmp"), std::string::npos) << s.error().message;
}

TEST_F(OutputCheck, WritableFilesPassAndLeaveNothing) {
  EXPECT_TRUE(check_output_file(dir_ / "stats.json").ok());
  EXPECT_TRUE(check_output_file(dir_ / "file.json").ok());  // replacing an existing file is fine
  EXPECT_TRUE(check_output_image(dir_ / "shot.png").ok());
  EXPECT_TRUE(check_output_image(dir_ / "shot.EXR").ok());
  EXPECT_TRUE(check_output_folder(dir_ / "new" / "deeper").ok());
  EXPECT_TRUE(check_output_folder(dir_ / "folder").ok());
  EXPECT_EQ(entries(), 2u);
}

TEST_F(OutputCheck, EachProblemIsNamed) {
  const std::string d = dir_.string();
  expect_error(check_output_file(dir_ / "missing" / "s.json"), ErrorCode::kIo, d + "/missing/s.json", "does not exist");
  expect_error(check_output_file(dir_ / "folder"), ErrorCode::kIo, d + "/folder", "is a folder");
  expect_error(check_output_image(dir_ / "folder"), ErrorCode::kIo, d + "/folder", "is a folder");
  expect_error(check_output_file(dir_ / "file.json" / "s.json"), ErrorCode::kIo, d + "/file.json/s.json", "not a folder");
  expect_error(check_output_image(dir_ / "shot.xyz"), ErrorCode::kUnsupported, d + "/shot.xyz", "\".xyz\"");
  expect_error(check_output_folder(dir_ / "file.json"), ErrorCode::kIo, d + "/file.json", "is a file");
  expect_error(check_output_folder(dir_ / "file.json" / "out"), ErrorCode::kIo, d + "/file.json/out", "not a folder");
  EXPECT_EQ(entries(), 2u);
}

// /proc refuses new files even to root, where permission bits would not.
TEST_F(OutputCheck, AFolderThatRefusesFilesIsFoundBeforeWriting) {
  expect_error(check_output_file("/proc/sylva_check.json"), ErrorCode::kIo, "/proc/sylva_check.json",
               "cannot create a file in the folder /proc");
  expect_error(check_output_image("/proc/sylva_check.png"), ErrorCode::kIo, "/proc/sylva_check.png", "/proc");
  expect_error(check_output_folder("/proc/sylva_check"), ErrorCode::kIo, "/proc/sylva_check", "/proc");
}

TEST_F(OutputCheck, AnInputIsNotAnOutput) {
  const std::vector<fs::path> inputs = {dir_ / "file.json"};
  expect_error(check_not_an_input(dir_ / "folder" / ".." / "file.json", inputs), ErrorCode::kIo,
               (dir_ / "folder" / ".." / "file.json").string(), "is an input of this run");
  EXPECT_TRUE(check_not_an_input(dir_ / "other.json", inputs).ok());
  EXPECT_TRUE(check_not_an_input(dir_ / "folder", inputs).ok());
}

}  // namespace
}  // namespace sylva
