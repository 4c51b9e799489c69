// Output files: atomic, all or nothing, never through a link planted in the folder.
#include "uavplan/io/files.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "uavplan/io/input_error.h"
#include "uavplan/io/io_test_fixtures.h"

namespace uavplan {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Links planted under every temporary name this process could take, and at the target itself:
// the write creates a fresh file, the links' targets keep their bytes, and the target is a file.
TEST(Files, PlantedLinksAreNeverWrittenThrough) {
  test::TempDir d("files_links");
  const fs::path victim = d.path / "victim.txt";
  std::ofstream(victim) << "precious";
  const std::string target = (d.path / "plan.json").string();
  for (int n = 0; n < 40; ++n)
    fs::create_symlink(victim, target + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(n));
  fs::create_symlink(victim, target + ".tmp." + std::to_string(::getpid()));
  fs::create_symlink(victim, target);
  write_file_atomic(target, "new plan");
  EXPECT_EQ(slurp(victim), "precious");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(target)));
  EXPECT_EQ(slurp(target), "new plan");
  write_file_atomic_in(target, "again");
  EXPECT_EQ(slurp(victim), "precious");
  EXPECT_EQ(slurp(target), "again");
}

// A file that cannot be written (a folder in its way) leaves the folder as it was: no file of the
// set renamed in, no temporary left.
TEST(Files, StagedFilesAreAllOrNothing) {
  test::TempDir d("files_staged");
  std::ofstream(d.path / "a.csv") << "old a";
  fs::create_directories(d.path / "b.csv");
  {
    StagedFiles staged(d.path.string());
    staged.add("a.csv", "new a");
    EXPECT_THROW(staged.add("b.csv", "new b"), OutputError);
  }
  EXPECT_EQ(slurp(d.path / "a.csv"), "old a");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d.path)) ++entries;
  EXPECT_EQ(entries, 2u);  // a.csv and the folder b.csv only
  {
    StagedFiles staged(d.path.string());
    staged.add("a.csv", "new a");
    staged.add("c.csv", "new c");
  }  // not committed: nothing changes
  EXPECT_EQ(slurp(d.path / "a.csv"), "old a");
  EXPECT_FALSE(fs::exists(d.path / "c.csv"));
  StagedFiles staged(d.path.string());
  staged.add("a.csv", "new a");
  staged.add("c.csv", "new c");
  staged.commit();
  EXPECT_EQ(slurp(d.path / "a.csv"), "new a");
  EXPECT_EQ(slurp(d.path / "c.csv"), "new c");
}

// The OS error is named in the message (here: a folder that cannot be created under a file).
TEST(Files, ErrorsNameTheFileAndTheOsError) {
  test::TempDir d("files_errors");
  std::ofstream(d.path / "file") << "x";
  try {
    write_file_atomic((d.path / "file" / "plan.json").string(), "x");
    FAIL() << "wrote under a file";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("ENOTDIR"), std::string::npos) << e.what();
  }
}

TEST(Files, EmptyOutputFolderIsBadInput) {
  EXPECT_THROW(check_output_dir(""), InputError);
  EXPECT_NO_THROW(check_output_dir("out"));
}

// Devices and FIFOs are refused before they are opened (a FIFO would block, /dev/zero never end).
TEST(Files, OnlyRegularFilesAreRead) {
  test::TempDir d("files_fifo");
  const fs::path fifo = d.path / "buildings.geojson";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(read_text_file(fifo.string()), InputError);
  EXPECT_THROW(read_text_file("/dev/zero"), InputError);
  std::ofstream(d.path / "ok.yaml") << "version: 1\n";
  EXPECT_EQ(read_text_file((d.path / "ok.yaml").string()), "version: 1\n");
}

// Temporaries of a process that is gone are removed; a link of that name is left alone.
TEST(Files, StaleTemporariesOfDeadProcessesOnly) {
  test::TempDir d("files_stale");
  const std::string dead = "999999999";  // above the kernel's largest pid
  std::ofstream(d.path / ("x.tmp." + dead + ".3")) << "left";
  std::ofstream(d.path / ("y.tmp." + std::to_string(::getpid()))) << "mine";
  fs::create_symlink(d.path / "y.tmp.1", d.path / ("z.tmp." + dead));
  remove_temporaries(d.path.string());
  EXPECT_FALSE(fs::exists(d.path / ("x.tmp." + dead + ".3")));
  EXPECT_TRUE(fs::exists(d.path / ("y.tmp." + std::to_string(::getpid()))));
  EXPECT_TRUE(fs::is_symlink(d.path / ("z.tmp." + dead)));
}

}  // namespace
}  // namespace uavplan
