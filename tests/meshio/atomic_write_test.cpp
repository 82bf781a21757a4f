#include "ffdkit/meshio/atomic_write.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace ffdkit::meshio {
namespace {

namespace fs = std::filesystem;

class AtomicWrite : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ffdkit-atomic-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string read(const fs::path& p) const {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& e : fs::directory_iterator(dir_)) n.push_back(e.path().filename().string());
    std::sort(n.begin(), n.end());
    return n;
  }
  fs::path dir_;
};

TEST_F(AtomicWrite, StagedFilesAppearOnlyWhenCommitted) {
  const fs::path target = dir_ / "out.txt";
  std::ofstream(target) << "old";
  {
    StagedFile staged(target, "new");
    EXPECT_EQ(read(target), "old");
    EXPECT_EQ(names().size(), 2u);
    staged.commit();
    EXPECT_EQ(read(target), "new");
  }
  { StagedFile abandoned(target, "newer"); }  // destroyed uncommitted
  EXPECT_EQ(read(target), "new");
  EXPECT_EQ(names(), std::vector<std::string>{"out.txt"});
}

TEST_F(AtomicWrite, TemporariesOfDeadWritersAreRemovedByTheNextWrite) {
  // A child process stages a file and exits without committing or cleaning (as if killed).
  const fs::path target = dir_ / "mesh.ply";
  const pid_t child = ::fork();
  if (child == 0) {
    auto* leaked = new StagedFile(target, "partial");
    (void)leaked;
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_EQ(names().size(), 1u);
  EXPECT_EQ(names()[0].rfind(".mesh.ply.tmp-" + std::to_string(child) + "-", 0), 0u) << names()[0];
  // Another file's temporaries and our own process's are not touched.
  std::ofstream(dir_ / ".other.ply.tmp-1-0") << "x";
  const std::string ours = ".mesh.ply.tmp-" + std::to_string(::getpid()) + "-999";
  std::ofstream(dir_ / ours) << "x";
  writeFileAtomically(target, "complete");
  EXPECT_EQ(read(target), "complete");
  EXPECT_EQ(names(), (std::vector<std::string>{".mesh.ply.tmp-" + std::to_string(::getpid()) + "-999", ".other.ply.tmp-1-0", "mesh.ply"}));
}

TEST_F(AtomicWrite, FailuresNameThePathAndTheStep) {
  try {
    writeFileAtomically(dir_ / "no-such-folder" / "x.txt", "x");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.txt: cannot write (create temporary file: No such file or directory)"), std::string::npos)
        << e.what();
  }
}

TEST_F(AtomicWrite, AStreamedFileHoldsEveryPieceInOrder) {
  const fs::path target = dir_ / "streamed.txt";
  std::string expected;
  StagedFile staged(target, [&](ByteSink& out) {
    for (int piece = 0; piece < 300; ++piece) {
      const std::string text = std::string(std::size_t(piece % 7) * 1000 + 1, char('a' + piece % 26)) + "\n";
      expected += text;
      out.write(text);
    }
    out.write("");  // an empty piece is allowed and writes nothing
  });
  EXPECT_FALSE(fs::exists(target));
  staged.commit();
  EXPECT_EQ(read(target), expected);
  EXPECT_EQ(names(), std::vector<std::string>{"streamed.txt"});
}

TEST_F(AtomicWrite, PartsWrittenAtTheirOffsetsFillOneStagedFile) {
  const fs::path target = dir_ / "joined.bin";
  StagedFile staged(target, "head:");
  // Out of order, as the ranks of a batch finish: each part at its offset, a child process too.
  writeStagedPart(staged.temporary(), target, 5 + 6, "world!");
  const pid_t child = ::fork();
  if (child == 0) {
    writeStagedPart(staged.temporary(), target, 5, "hello ");
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_FALSE(fs::exists(target));
  staged.commit();
  EXPECT_EQ(read(target), "head:hello world!");
  EXPECT_EQ(names(), std::vector<std::string>{"joined.bin"});
  try {
    writeStagedPart(dir_ / ".gone.tmp-1-1", target, 0, "x");
    FAIL() << "wrote into a temporary that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string() + ": cannot write (open the temporary file"), std::string::npos) << e.what();
  }
}

TEST_F(AtomicWrite, AProducerThatFailsLeavesTheOldFileAndNoTemporary) {
  const fs::path target = dir_ / "out.txt";
  std::ofstream(target) << "old";
  struct ProducerFailed {};
  EXPECT_THROW(StagedFile(target, [](ByteSink& out) {
                 out.write("half of the file");
                 throw ProducerFailed{};
               }),
               ProducerFailed);
  EXPECT_EQ(read(target), "old");
  EXPECT_EQ(names(), std::vector<std::string>{"out.txt"});
}

}  // namespace
}  // namespace ffdkit::meshio
