// Input files: a directory, a FIFO, a device and an oversized file are refused by name before
// anything reads them (a FIFO would block, /dev/zero would read forever); a regular file is
// read whole.
#include "wirerig/io/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / "wirerig_input_file_test";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

void ExpectRefused(const fs::path& path, const std::string& reason) {
  SCOPED_TRACE(path.string());
  const Result<std::string> read = ReadInputFile(path, "scene file (JSON)");
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().rfind(path.string() + ": ", 0), 0u) << read.error();
  EXPECT_NE(read.error().find(reason), std::string::npos) << read.error();
  const Result<std::uintmax_t> checked = CheckInputFile(path, "scene file (JSON)", 1000);
  ASSERT_FALSE(checked.ok());
  EXPECT_NE(checked.error().find(reason), std::string::npos) << checked.error();
}

TEST(InputFile, ReadsARegularFileWhole) {
  const fs::path path = Scratch("good.json");
  std::ofstream(path) << "{\"a\": 1}";
  const Result<std::string> read = ReadInputFile(path, "scene file (JSON)");
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read.value(), "{\"a\": 1}");
  const Result<std::uintmax_t> checked = CheckInputFile(path, "scene file (JSON)", 8);
  ASSERT_TRUE(checked.ok()) << checked.error();
  EXPECT_EQ(checked.value(), 8u);
}

TEST(InputFile, RefusesAMissingFile) { ExpectRefused(Scratch("missing.json"), "no such file"); }

TEST(InputFile, RefusesADirectory) {
  const fs::path dir = Scratch("folder.json");
  fs::create_directories(dir);
  ExpectRefused(dir, "is a directory, not a scene file (JSON)");
}

TEST(InputFile, RefusesAFifoWithoutBlocking) {
  const fs::path path = Scratch("pipe.json");
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  ExpectRefused(path, "is not a regular file");  // a blocking open would hang here
  fs::remove(path);
}

TEST(InputFile, RefusesADeviceThatNeverEnds) { ExpectRefused("/dev/zero", "not a regular file"); }

TEST(InputFile, RefusesAFileOverTheLimitBeforeReadingIt) {
  const fs::path path = Scratch("big.json");
  std::ofstream(path) << std::string(1001, ' ');
  const Result<std::string> read = ReadInputFile(path, "scene file (JSON)", 1000);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error(), path.string() +
                              ": is 1001 bytes, more than the 1000 bytes a scene file (JSON) "
                              "may have");
  EXPECT_TRUE(ReadInputFile(path, "scene file (JSON)", 1001).ok());
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
