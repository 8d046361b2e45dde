// Whole-file writes replace a regular file or make a new one, and nothing else: a device, a FIFO,
// a socket or a folder at the final name is refused and left as it was (issue 31, class 3: run as
// root, `--junit /dev/null` replaced the system's /dev/null with a regular file).
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"

namespace asperity::io {
namespace {
namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("asperity_atomic_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string text_of(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, MakesANewFileAndReplacesARegularOne) {
  const fs::path dir = fresh_dir("regular");
  write_atomically(dir / "a.txt", "one");
  EXPECT_EQ(text_of(dir / "a.txt"), "one");
  write_atomically(dir / "a.txt", "two");
  EXPECT_EQ(text_of(dir / "a.txt"), "two");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, NeverReplacesAFolderAFifoOrADevice) {
  const fs::path dir = fresh_dir("special");
  fs::create_directories(dir / "folder");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0666), 0);
  const bool device = ::mknod((dir / "null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
  fs::create_symlink(dir / "fifo", dir / "link-to-fifo");
  for (const char* name : {"folder", "fifo", "null", "link-to-fifo"}) {
    if (std::string(name) == "null" && !device) continue;  // mknod needs root
    const fs::file_status before = fs::symlink_status(dir / name);
    EXPECT_THROW(write_atomically(dir / name, "x"), std::runtime_error) << name;
    EXPECT_THROW(remove_earlier_output(dir / name), InputError) << name;
    EXPECT_EQ(fs::symlink_status(dir / name).type(), before.type()) << name;
    EXPECT_NE(not_replaceable(dir / name), "") << name;
  }
  if (device) {
    EXPECT_EQ(not_replaceable(dir / "null"), "a device");
  }
  EXPECT_EQ(not_replaceable(dir / "folder"), "a folder");
  EXPECT_EQ(not_replaceable(dir / "link-to-fifo"), "a link to a FIFO");
  // No temporary was left beside them.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

// Something of another's at the temporary's name is neither written through nor removed.
TEST(AtomicFile, NeverTakesOrRemovesATemporaryItDidNotMake) {
  const fs::path dir = fresh_dir("theirs");
  const fs::path file = dir / "out.txt";
  const fs::path tmp = file.string() + ".partial-" + std::to_string(::getpid());
  fs::create_directories(tmp);
  EXPECT_THROW(write_atomically(file, "x"), std::runtime_error);
  EXPECT_TRUE(fs::is_directory(tmp));
  EXPECT_FALSE(fs::exists(file));
  fs::remove_all(dir);
}

TEST(AtomicFile, AnEarlierOutputGoesButNotWhatALinkPointsTo) {
  const fs::path dir = fresh_dir("earlier");
  std::ofstream(dir / "old.csv") << "1";
  remove_earlier_output(dir / "old.csv");
  EXPECT_FALSE(fs::exists(dir / "old.csv"));
  remove_earlier_output(dir / "never-there.csv");  // nothing there: nothing to do
  std::ofstream(dir / "target.csv") << "2";
  fs::create_symlink(dir / "target.csv", dir / "link.csv");
  remove_earlier_output(dir / "link.csv");
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "link.csv")));
  EXPECT_EQ(text_of(dir / "target.csv"), "2");
  fs::remove_all(dir);
}

// A peer's output folder is emptied before its run: what an earlier run left goes (files, links,
// subfolders), but never through a link: the folder itself a link, or a link inside it, leaves
// the target's files in place, and a FIFO inside refuses before anything is removed.
TEST(AtomicFile, AnOutputFolderIsEmptiedNeverThroughALink) {
  const fs::path dir = fresh_dir("peer-folder");
  const fs::path elsewhere = fresh_dir("peer-elsewhere");
  std::ofstream(elsewhere / "keep.txt") << "mine";
  // Emptied: a file, a nested folder, a link to the outside folder (the link goes, not its target).
  fs::create_directories(dir / "run" / "scratch");
  std::ofstream(dir / "run" / "force.csv") << "1";
  std::ofstream(dir / "run" / "scratch" / "log") << "2";
  fs::create_directory_symlink(elsewhere, dir / "run" / "link");
  empty_output_folder(dir / "run");
  EXPECT_TRUE(fs::is_directory(dir / "run"));
  EXPECT_TRUE(fs::is_empty(dir / "run"));
  EXPECT_EQ(text_of(elsewhere / "keep.txt"), "mine");
  // Absent: created.
  empty_output_folder(dir / "new");
  EXPECT_TRUE(fs::is_directory(dir / "new"));
  // The folder itself a link to another folder: refused, the target untouched.
  fs::create_directory_symlink(elsewhere, dir / "linked");
  EXPECT_THROW(empty_output_folder(dir / "linked"), InputError);
  EXPECT_EQ(text_of(elsewhere / "keep.txt"), "mine");
  // A FIFO inside: refused before anything goes.
  std::ofstream(dir / "run" / "a.csv") << "3";
  ASSERT_EQ(::mkfifo((dir / "run" / "pipe").c_str(), 0600), 0);
  EXPECT_THROW(empty_output_folder(dir / "run"), InputError);
  EXPECT_EQ(text_of(dir / "run" / "a.csv"), "3");
  // A regular file where the folder goes: refused, kept.
  std::ofstream(dir / "file") << "4";
  EXPECT_THROW(empty_output_folder(dir / "file"), InputError);
  EXPECT_EQ(text_of(dir / "file"), "4");
  fs::remove_all(dir);
  fs::remove_all(elsewhere);
}

}  // namespace
}  // namespace asperity::io
