// Saves that never lose a user's file: atomic single-file writes and multi-file transactions,
// with the old files put at risk by injected failures (file_fault.hpp) at the same paths.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/file_fault.hpp>
#include <sylva/core/file_transaction.hpp>
#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using sylva::FileFaultPoint;
using sylva::FileTransaction;
using sylva::ScopedFileFault;

namespace {

class FileSave : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sylva_file_save_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "maps");
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_ / "scene.json", fs::perms::owner_all, ec);
    fs::remove_all(dir_, ec);
  }
  void put(const fs::path& p, const std::string& text) { ASSERT_TRUE(sylva::write_file_atomic(p, text).ok()); }
  std::string get(const fs::path& p) { return sylva::read_file(p).value_or("<missing>"); }
  // Only the files a user would see: no temporary or old-file link left behind.
  std::vector<std::string> listing() {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) names.push_back(fs::relative(e.path(), dir_).string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

auto fails_at(const std::string& name, FileFaultPoint point) {
  return [name, point](const fs::path& target, FileFaultPoint p) { return p == point && target.filename() == name; };
}

}  // namespace

TEST_F(FileSave, AtomicWriteReplacesTheFileWhole) {
  put(dir_ / "a.txt", "old");
  put(dir_ / "a.txt", "new content");
  EXPECT_EQ(get(dir_ / "a.txt"), "new content");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.txt", "maps"}));
}

TEST_F(FileSave, DiskFullHalfWayKeepsTheOldFile) {
  put(dir_ / "a.txt", "old content that must survive");
  {
    ScopedFileFault fault(fails_at("a.txt", FileFaultPoint::kWrite));
    sylva::Status s = sylva::write_file_atomic(dir_ / "a.txt", std::string(4096, 'x'));
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find((dir_ / "a.txt").string()), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find("No space left"), std::string::npos) << s.error().message;
  }
  EXPECT_EQ(get(dir_ / "a.txt"), "old content that must survive");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.txt", "maps"}));
}

TEST_F(FileSave, FailedImageWriteKeepsTheOldImage) {
  sylva::Image old(4, 4, 1);
  old.at(1, 1, 0) = 1.0f;
  ASSERT_TRUE(sylva::write_image(dir_ / "m.png", old).ok());
  const std::string before = get(dir_ / "m.png");
  ScopedFileFault fault(fails_at("m.png", FileFaultPoint::kRename));
  EXPECT_FALSE(sylva::write_image(dir_ / "m.png", sylva::Image(8, 8, 1)).ok());
  EXPECT_EQ(get(dir_ / "m.png"), before);
  EXPECT_EQ(listing(), (std::vector<std::string>{"m.png", "maps"}));
}

TEST_F(FileSave, ReadOnlyTargetIsRefusedNotReplaced) {
  put(dir_ / "scene.json", "mine");
  fs::permissions(dir_ / "scene.json", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  sylva::Status s = sylva::write_file_atomic(dir_ / "scene.json", "theirs");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("read-only"), std::string::npos) << s.error().message;
  EXPECT_EQ(get(dir_ / "scene.json"), "mine");
  EXPECT_EQ(fs::status(dir_ / "scene.json").permissions() & fs::perms::owner_write, fs::perms::none);
  FileTransaction t;
  EXPECT_FALSE(t.stage_bytes(dir_ / "scene.json", "theirs").ok());
  EXPECT_EQ(get(dir_ / "scene.json"), "mine");
}

TEST_F(FileSave, MissingFolderAndFolderTargetNameTheUsersPath) {
  sylva::Status missing = sylva::write_file_atomic(dir_ / "nope" / "a.txt", "x");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find((dir_ / "nope" / "a.txt").string()), std::string::npos);
  EXPECT_NE(missing.error().message.find("does not exist"), std::string::npos) << missing.error().message;
  sylva::Status folder = sylva::write_image(dir_ / "maps", sylva::Image(2, 2, 1));
  ASSERT_FALSE(folder.ok());
  EXPECT_NE(folder.error().message.find("is a folder"), std::string::npos) << folder.error().message;
  EXPECT_EQ(folder.error().message.find(".tmp"), std::string::npos) << folder.error().message;
}

TEST_F(FileSave, TransactionCommitsEveryFile) {
  put(dir_ / "maps" / "h.txt", "old map");
  put(dir_ / "scene.json", "old scene");
  FileTransaction t;
  ASSERT_TRUE(t.stage_bytes(dir_ / "maps" / "h.txt", "new map").ok());
  ASSERT_TRUE(t.stage_bytes(dir_ / "maps" / "d.txt", "new density").ok());
  ASSERT_TRUE(t.stage_bytes(dir_ / "scene.json", "new scene").ok());
  EXPECT_EQ(get(dir_ / "maps" / "h.txt"), "old map") << "staging touches no user file";
  ASSERT_TRUE(t.commit().ok());
  EXPECT_EQ(get(dir_ / "maps" / "h.txt"), "new map");
  EXPECT_EQ(get(dir_ / "maps" / "d.txt"), "new density");
  EXPECT_EQ(get(dir_ / "scene.json"), "new scene");
  EXPECT_EQ(listing(), (std::vector<std::string>{"maps", "maps/d.txt", "maps/h.txt", "scene.json"}));
}

// The case that lost work: maps renamed, then the scene's rename fails. Every old file returns.
TEST_F(FileSave, FailedLastRenameRestoresTheFilesAlreadyRenamed) {
  put(dir_ / "maps" / "h.txt", "old map");
  put(dir_ / "scene.json", "old scene");
  ScopedFileFault fault(fails_at("scene.json", FileFaultPoint::kRename));
  FileTransaction t;
  ASSERT_TRUE(t.stage_bytes(dir_ / "maps" / "h.txt", "new map").ok());
  ASSERT_TRUE(t.stage_bytes(dir_ / "maps" / "d.txt", "new density").ok());
  ASSERT_TRUE(t.stage_bytes(dir_ / "scene.json", "new scene").ok());
  sylva::Status s = t.commit();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("scene.json"), std::string::npos) << s.error().message;
  EXPECT_EQ(get(dir_ / "maps" / "h.txt"), "old map");
  EXPECT_EQ(get(dir_ / "scene.json"), "old scene");
  EXPECT_EQ(listing(), (std::vector<std::string>{"maps", "maps/h.txt", "scene.json"})) << "new files removed";
}

TEST_F(FileSave, FailedStageLeavesNothingBehind) {
  put(dir_ / "maps" / "h.txt", "old map");
  {
    FileTransaction t;
    ASSERT_TRUE(t.stage_bytes(dir_ / "maps" / "h.txt", "new map").ok());
    ScopedFileFault fault(fails_at("scene.json", FileFaultPoint::kWrite));
    EXPECT_FALSE(t.stage_bytes(dir_ / "scene.json", "new scene").ok());
  }  // abandoned: its temporaries go
  EXPECT_EQ(get(dir_ / "maps" / "h.txt"), "old map");
  EXPECT_EQ(listing(), (std::vector<std::string>{"maps", "maps/h.txt"}));
}

TEST_F(FileSave, SameTargetTwiceIsRefused) {
  FileTransaction t;
  ASSERT_TRUE(t.stage_bytes(dir_ / "a.txt", "1").ok());
  EXPECT_FALSE(t.stage_bytes(dir_ / "maps" / ".." / "a.txt", "2").ok());
}
