// read_capped_file: a file read whole never beyond its limit, whatever it is.
#include "frontend/capped_file.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace mbfe::frontend {
namespace {

namespace fs = std::filesystem;

class CappedFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("mbfe_capped_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  fs::path dir_;
};

TEST_F(CappedFile, AFileUpToTheLimitIsReadWhole) {
  const std::string text(70000, 'x');  // more than one block of 64 KiB
  const CappedRead read = read_capped_file(write("a.txt", text), text.size(), FileKinds::kRegularOnly);
  ASSERT_TRUE(read) << read.why;
  EXPECT_EQ(read.text, text);
  EXPECT_TRUE(read_capped_file(write("empty.txt", ""), 0, FileKinds::kRegularOnly));
}

TEST_F(CappedFile, ALargerRegularFileIsRefusedByItsSize) {
  // A sparse file of 1 GiB (no disk space): refused before a byte is read
  // (reading it took a minute and gigabytes of memory).
  const std::string path = write("sparse.csv", "");
  ASSERT_EQ(::truncate(path.c_str(), off_t{1} << 30), 0);
  const CappedRead read = read_capped_file(path, 1000, FileKinds::kRegularOnly);
  EXPECT_EQ(read.fault, ReadFault::kTooLarge);
  EXPECT_EQ(read.why, "the file is 1073741824 bytes, more than the limit of 1000");
  EXPECT_TRUE(read.text.empty());
  EXPECT_EQ(read_capped_file(write("b.txt", "12345"), 4, FileKinds::kRegularOnly).fault, ReadFault::kTooLarge);
}

TEST_F(CappedFile, ADeviceIsRefusedOrReadOnlyToTheLimit) {
  // /dev/zero never ends: refused where only regular files are taken, and
  // read one block past the limit at most where streams are.
  CappedRead read = read_capped_file("/dev/zero", 1 << 20, FileKinds::kRegularOnly);
  EXPECT_EQ(read.fault, ReadFault::kNotRegular);
  EXPECT_EQ(read.why, "cannot read: not a regular file (a folder, a device or a pipe)");
  read = read_capped_file("/dev/zero", 1 << 20, FileKinds::kAlsoStreams);
  EXPECT_EQ(read.fault, ReadFault::kTooLarge);
  EXPECT_EQ(read.why, "the file is more than the limit of 1048576 bytes");
}

TEST_F(CappedFile, FoldersPipesAndMissingFilesAreRefusedBeforeReading) {
  EXPECT_EQ(read_capped_file(dir_.string(), 100, FileKinds::kRegularOnly).fault, ReadFault::kFolder);
  EXPECT_EQ(read_capped_file(dir_.string(), 100, FileKinds::kAlsoStreams).fault, ReadFault::kFolder);
  // A pipe nobody writes would block the reader for ever.
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(read_capped_file(fifo.string(), 100, FileKinds::kRegularOnly).fault, ReadFault::kNotRegular);
  const CappedRead missing = read_capped_file((dir_ / "missing").string(), 100, FileKinds::kRegularOnly);
  EXPECT_EQ(missing.fault, ReadFault::kCannotRead);
  EXPECT_EQ(missing.why, "cannot read: No such file or directory");
}

}  // namespace
}  // namespace mbfe::frontend
