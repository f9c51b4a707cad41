// Tests for CheckOutputFile: extension, directory, missing and unwritable folders, nothing
// written by the check.
#include "wirerig/io/output_file.h"

#include "wirerig/io/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

namespace fs = std::filesystem;

fs::path Scratch() {
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("wirerig_output_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

void ExpectRefused(const fs::path& path, std::initializer_list<std::string_view> extensions,
                   const std::string& reason) {
  const Result<bool> checked = CheckOutputFile(path, extensions);
  ASSERT_FALSE(checked.ok()) << path;
  EXPECT_EQ(checked.error(), path.string() + ": " + reason);
}

TEST(CheckOutputFile, AcceptsAWritableFolderAndAListedExtension) {
  const fs::path path = Scratch() / "out.GLB";  // case-insensitive
  EXPECT_TRUE(CheckOutputFile(path, {".glb", ".gltf"}).ok());
  EXPECT_FALSE(fs::exists(path));  // nothing written
  EXPECT_TRUE(CheckOutputFile(Scratch() / "anything.bin", {}).ok());
}

TEST(CheckOutputFile, RefusesOtherExtensions) {
  ExpectRefused(Scratch() / "m.fbx", {".glb", ".gltf"},
                "the output must be a .glb or .gltf file (not .fbx)");
  ExpectRefused(Scratch() / "m", {".png"}, "the output must be a .png file (it has no extension)");
}

TEST(CheckOutputFile, NamesTheMissingFolderOnce) {
  const fs::path missing = Scratch() / "no" / "such" / "folder" / "x.png";
  ExpectRefused(missing, {".png"}, "the folder " + (Scratch() / "no").string() + " does not exist");
}

TEST(CheckOutputFile, RefusesADirectoryAndAFileAsFolder) {
  const fs::path dir = Scratch() / "d.png";
  fs::create_directories(dir);
  ExpectRefused(dir, {".png"}, "is a directory, not a file to write");
  const fs::path file = Scratch() / "plain";
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fclose(f);
  }
  ExpectRefused(file / "x.png", {".png"}, file.string() + " is not a folder");
}

// Writing renames a new file over the target: onto a FIFO, a device or a symbolic link that
// replaced the FIFO, the device (as root, /dev/full was destroyed) or the link. Refused by the
// check and by the atomic writer itself, naming the file; the target is left as it was.
TEST(CheckOutputFile, RefusesDevicesFifosAndLinks) {
  const fs::path fifo = Scratch() / "pipe.json";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path target = Scratch() / "real.json";
  { std::fclose(std::fopen(target.c_str(), "w")); }
  const fs::path link = Scratch() / "link.json";
  fs::remove(link);
  fs::create_symlink(target, link);
  const char* kDevice =
      "is not a regular file (a device, FIFO or socket): writing would replace it";
  ExpectRefused(fifo, {}, kDevice);
  ExpectRefused("/dev/null", {}, kDevice);  // checked only: nothing is written
  ExpectRefused(link, {},
                "is a symbolic link: give the file it points to (writing would replace "
                "the link)");
  for (const fs::path& path : {fifo, link}) {
    const Result<fs::path> written = WriteFileAtomically(path, "{}");
    ASSERT_FALSE(written.ok()) << path;
    EXPECT_EQ(written.error().rfind(path.string() + ": is ", 0), 0u) << written.error();
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_symlink(link));
  fs::remove(fifo);
  fs::remove(link);
}

// A legal 250-byte name failed only after the work, when its temporary name did not fit.
TEST(CheckOutputFile, RefusesANameTooLongForItsTemporaryFile) {
  const fs::path path = Scratch() / (std::string(246, 'n') + ".glb");
  ExpectRefused(path, {".glb"}, "the file name is too long (250 bytes; at most 243)");
  EXPECT_TRUE(CheckOutputFile(Scratch() / (std::string(239, 'n') + ".glb"), {".glb"}).ok());
}

// As root every folder's permission bits allow writing, /sys's too: the bake then ran in full
// before the write failed. The probe finds it; a folder that can be written keeps no probe.
TEST(CheckOutputFile, ProbesTheFolderWherePermissionBitsDoNotTell) {
  const Result<bool> checked = CheckOutputFile("/sys/wirerig_x.glb", {".glb"});
  ASSERT_FALSE(checked.ok());
  EXPECT_EQ(checked.error().rfind("/sys/wirerig_x.glb: the folder /sys is not writable", 0), 0u)
      << checked.error();
  ASSERT_TRUE(CheckOutputFile(Scratch() / "probe.glb", {".glb"}).ok());
  for (const auto& entry : fs::directory_iterator(Scratch()))
    EXPECT_EQ(entry.path().filename().string().rfind(".wirerig-probe", 0), std::string::npos)
        << entry.path();
}

TEST(CheckOutputFile, RefusesAnUnwritableFolder) {
  const fs::path dir = Scratch() / "locked";
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  // Root writes anywhere: drop the effective uid for the check (the saved uid stays 0).
  const bool root = ::geteuid() == 0;
  if (root) {
    ASSERT_EQ(::seteuid(65534), 0);
  }
  const Result<bool> checked = CheckOutputFile(dir / "x.png", {".png"});
  if (root) {
    ASSERT_EQ(::seteuid(0), 0);
  }
  fs::permissions(dir, fs::perms::owner_all);
  ASSERT_FALSE(checked.ok());
  EXPECT_EQ(checked.error(),
            (dir / "x.png").string() + ": the folder " + dir.string() + " is not writable");
}

std::string Contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The same file through another spelling or a hard link is refused; another file, or one
// that does not exist, passes.
TEST(CheckNotAnInput, RefusesTheInputThroughAnyPath) {
  const fs::path dir = Scratch() / "inputs";
  fs::create_directories(dir / "sub");
  const fs::path mesh = dir / "mesh.gltf";
  std::ofstream(mesh) << "{}";
  const fs::path other_spelling = dir / "sub" / ".." / "mesh.gltf";
  const Result<bool> same = CheckNotAnInput(other_spelling, mesh, "the scene's mesh");
  ASSERT_FALSE(same.ok());
  EXPECT_EQ(same.error(), other_spelling.string() + ": is the scene's mesh (" + mesh.string() +
                              "), which this command reads; write elsewhere");
  fs::create_hard_link(mesh, dir / "linked.gltf");
  EXPECT_FALSE(CheckNotAnInput(dir / "linked.gltf", mesh, "the scene's mesh").ok());
  std::ofstream(dir / "other.gltf") << "{}";
  EXPECT_TRUE(CheckNotAnInput(dir / "other.gltf", mesh, "the scene's mesh").ok());
  EXPECT_TRUE(CheckNotAnInput(dir / "new.gltf", mesh, "the scene's mesh").ok());
  EXPECT_TRUE(CheckNotAnInput(dir / "new.gltf", dir / "absent.gltf", "the scene's mesh").ok());
}

// Several files: when one cannot be written, none of the old ones is replaced and no
// temporary file stays; otherwise all are.
TEST(WriteFilesAtomically, WritesAllOrNothing) {
  const fs::path dir = Scratch() / "all_or_nothing";
  fs::remove_all(dir);
  fs::create_directories(dir / "b.wclip");  // a directory where the second file would go
  std::ofstream(dir / "a.wrig") << "OLD";
  const std::vector<FileToWrite> files = {{dir / "a.wrig", "NEW A"}, {dir / "b.wclip", "NEW B"}};
  const Result<std::vector<fs::path>> failed = WriteFilesAtomically(files);
  ASSERT_FALSE(failed.ok());
  EXPECT_NE(failed.error().find("none of the 2 files was replaced"), std::string::npos)
      << failed.error();
  EXPECT_EQ(Contents(dir / "a.wrig"), "OLD");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);

  fs::remove(dir / "b.wclip");
  const Result<std::vector<fs::path>> written = WriteFilesAtomically(files);
  ASSERT_TRUE(written.ok()) << written.error();
  EXPECT_EQ(written.value(), (std::vector<fs::path>{dir / "a.wrig", dir / "b.wclip"}));
  EXPECT_EQ(Contents(dir / "a.wrig"), "NEW A");
  EXPECT_EQ(Contents(dir / "b.wclip"), "NEW B");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
