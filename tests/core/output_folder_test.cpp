#include "core/io/output_folder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/yaml_reader.h"

namespace coopmap {
namespace {

namespace fs = std::filesystem;

class OutputFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("coopmap_output_folder_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  static void write(const fs::path& file, const std::string& text) {
    writeFileAtomic(file.string(), text);
  }
  // Every entry of the test's folder, by name.
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(root_)) out.push_back(e.path().filename());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path root_;
};

TEST_F(OutputFolderTest, CommitPutsTheOutputsInPlaceWithTheMarker) {
  {
    OutputFolder out(root_ / "out", "test");
    EXPECT_NE(out.path(), root_ / "out");
    EXPECT_FALSE(fs::exists(root_ / "out"));  // nothing there until commit
    write(out.path() / "a.txt", "new");
    out.commit();
  }
  EXPECT_EQ(readFile((root_ / "out" / "a.txt").string()), "new");
  EXPECT_EQ(readFile((root_ / "out" / kOutputMarker).string()), "test\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"out"});
}

TEST_F(OutputFolderTest, ACommitReplacesEverythingAnEarlierRunWrote) {
  for (const char* file : {"map_eric.pgm", "map_jose.pgm"}) {
    OutputFolder out(root_ / "out", "test");
    write(out.path() / file, file);
    out.commit();
  }
  EXPECT_FALSE(fs::exists(root_ / "out" / "map_eric.pgm"));
  EXPECT_TRUE(fs::exists(root_ / "out" / "map_jose.pgm"));
  EXPECT_EQ(entries(), std::vector<std::string>{"out"});
}

TEST_F(OutputFolderTest, WithoutCommitTheFolderStaysAsItWasAndNothingIsLeftBeside) {
  {
    OutputFolder out(root_ / "out", "test");
    write(out.path() / "a.txt", "first");
    out.commit();
  }
  {
    OutputFolder out(root_ / "out", "test");
    write(out.path() / "a.txt", "second, cut short");
    write(out.path() / "b.txt", "second");
  }  // e.g. an exception while writing
  EXPECT_EQ(readFile((root_ / "out" / "a.txt").string()), "first");
  EXPECT_FALSE(fs::exists(root_ / "out" / "b.txt"));
  EXPECT_EQ(entries(), std::vector<std::string>{"out"});
}

TEST_F(OutputFolderTest, AFolderOfOtherFilesIsRefusedAndLeftAlone) {
  fs::create_directories(root_ / "mine");
  write(root_ / "mine" / "thesis.tex", "years of work");
  EXPECT_NE(outputFolderProblem((root_ / "mine").string()).find("holds other files"),
            std::string::npos);
  EXPECT_THROW(OutputFolder(root_ / "mine", "test"), ConfigError);
  EXPECT_EQ(readFile((root_ / "mine" / "thesis.tex").string()), "years of work");
  EXPECT_EQ(entries(), std::vector<std::string>{"mine"});
  // An empty folder, or one named with a trailing separator, is fine.
  fs::create_directories(root_ / "empty");
  EXPECT_EQ(outputFolderProblem((root_ / "empty").string()), "");
  OutputFolder out((root_ / "empty").string() + "/", "test");
  out.commit();
  EXPECT_TRUE(fs::exists(root_ / "empty" / kOutputMarker));
  write(root_ / "a_file", "x");
  EXPECT_NE(outputFolderProblem((root_ / "a_file").string()).find("is a file"), std::string::npos);
  EXPECT_NE(outputFolderProblem("").find("got ''"), std::string::npos);
}

TEST_F(OutputFolderTest, AKilledRunsStagingFolderIsRemovedByTheNextOne) {
  // A process id above any the kernel hands out: that process is gone.
  const fs::path orphan = root_ / "out.partial-2147483600";
  fs::create_directories(orphan);
  write(orphan / "half.pgm", "half");
  // Another live process's staging folder (this one's parent's id) is not touched.
  const fs::path live = root_ / ("out.partial-" + std::to_string(::getppid()));
  fs::create_directories(live);
  {
    OutputFolder out(root_ / "out", "test");
    out.commit();
  }
  EXPECT_FALSE(fs::exists(orphan));
  EXPECT_TRUE(fs::exists(live));
}

}  // namespace
}  // namespace coopmap
