// Files beside an output (io/file_kind.hpp): a lock, a fold's .partial, a journal and an
// output's temporary are made exclusively and never written through a symbolic link or a
// second name of another file; a file read is a regular file opened without blocking (a FIFO
// is refused at once); a sparse journal is not checksummed byte by byte; a command stopped by
// SIGTERM leaves no temporary.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <string>

#include "pcrf/io/atomic_file.hpp"
#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/io/record_log.hpp"
#include "pcrf/io/run_lock.hpp"
#include "support/test_support.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;
using test::read_file;

constexpr const char* kStudyText = "[study]\nname = \"precious\"\n";

/// What constructing with `make` throws (empty: nothing).
template <class Make>
std::string refusal(Make make) {
  try {
    make();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

/// A folder with the user's study file and `sidecar` a symbolic link to it.
fs::path with_link(const std::string& name, const fs::path& sidecar_name) {
  const auto dir = test::scratch_dir(name);
  test::write_file(dir, "study.toml", kStudyText);
  fs::create_symlink(dir / "study.toml", dir / sidecar_name);
  return dir;
}

TEST(Sidecar, ALockIsNeverWrittenThroughALinkOrASecondName) {
  auto dir = with_link("sidecar_lock_link", "c.h5.lock");
  std::string why = refusal([&] { RunLock lock(dir / "c.h5"); });
  EXPECT_NE(why.find((dir / "c.h5.lock").string() + ": is a symbolic link; pcrf makes its lock file itself"), std::string::npos) << why;
  EXPECT_EQ(read_file(dir / "study.toml"), kStudyText);
  EXPECT_EQ(RunLock::holder(dir / "c.h5"), "");  // nothing followed to look either
  // A hard link: a regular file, but the study file's second name.
  dir = test::scratch_dir("sidecar_lock_hard");
  test::write_file(dir, "study.toml", kStudyText);
  fs::create_hard_link(dir / "study.toml", dir / "c.h5.lock");
  why = refusal([&] { RunLock lock(dir / "c.h5"); });
  EXPECT_NE(why.find("has 2 names"), std::string::npos) << why;
  EXPECT_EQ(read_file(dir / "study.toml"), kStudyText);
  // A FIFO: refused at once, not waited on.
  dir = test::scratch_dir("sidecar_lock_fifo");
  ASSERT_EQ(::mkfifo((dir / "c.h5.lock").c_str(), 0600), 0);
  why = refusal([&] { RunLock lock(dir / "c.h5"); });
  EXPECT_NE(why.find("is a FIFO"), std::string::npos) << why;
  EXPECT_EQ(RunLock::holder(dir / "c.h5"), "");
  // A killed run's lock (a regular file of one name) is reused.
  dir = test::scratch_dir("sidecar_lock_stale");
  test::write_file(dir, "c.h5.lock", "pid 1 on host gone\n");
  RunLock lock(dir / "c.h5");
  EXPECT_NE(read_file(dir / "c.h5.lock").find("pid " + std::to_string(::getpid())), std::string::npos);
}

TEST(Sidecar, APartialIsMadeExclusivelyAndAKilledRunsOneReplaced) {
  auto dir = with_link("sidecar_partial_link", "c.h5.partial");
  const std::string why = refusal([&] { AtomicFile f(dir / "c.h5", true, AtomicFile::Temporary::kPartial); });
  EXPECT_NE(why.find((dir / "c.h5.partial").string() + ": is a symbolic link"), std::string::npos) << why;
  EXPECT_EQ(read_file(dir / "study.toml"), kStudyText);
  // A killed run's .partial is replaced, not truncated in place: a second name of it keeps its content.
  dir = test::scratch_dir("sidecar_partial_stale");
  test::write_file(dir, "c.h5.partial", "half a cube");
  {
    AtomicFile f(dir / "c.h5", true, AtomicFile::Temporary::kPartial);
    f.write("new", 3);
    f.commit();
  }
  EXPECT_EQ(read_file(dir / "c.h5"), "new");
  EXPECT_FALSE(fs::exists(dir / "c.h5.partial"));
}

TEST(Sidecar, AJournalIsNeverWrittenThroughALink) {
  auto dir = with_link("sidecar_journal_link", "c.h5.journal");
  const auto journal = dir / "c.h5.journal";
  EXPECT_NE(refusal([&] { LogWriter w(journal, 0); }).find(journal.string() + ": is a symbolic link; pcrf makes its journal itself"),
            std::string::npos);
  EXPECT_NE(refusal([&] { LogWriter w(journal, 8); }).find("is a symbolic link"), std::string::npos);
  EXPECT_NE(refusal([&] { LogReader r(journal); }).find(journal.string() + ": is a symbolic link, not a regular file"),
            std::string::npos);
  EXPECT_EQ(read_file(dir / "study.toml"), kStudyText);
  // A stale journal is replaced by a new one (made exclusively), not truncated through a second name.
  dir = test::scratch_dir("sidecar_journal_stale");
  test::write_file(dir, "old.journal", "pcrf-log and old records");
  fs::create_hard_link(dir / "old.journal", dir / "c.h5.journal");
  EXPECT_NE(refusal([&] { LogWriter w(dir / "c.h5.journal", 0); }).find("has 2 names"), std::string::npos);
  fs::remove(dir / "old.journal");
  {
    LogWriter w(dir / "c.h5.journal", 0);
    w.add(7, "x");
    w.sync();
  }
  const LogReader read(dir / "c.h5.journal");
  ASSERT_EQ(read.records().size(), 1u);
  EXPECT_EQ(read.payload(read.records()[0]), "x");
}

TEST(Sidecar, AFifoIsRefusedAtOnceWhereAFileIsReadOrAnOutputWritten) {
  const auto dir = test::scratch_dir("sidecar_fifo");
  ASSERT_EQ(::mkfifo((dir / "c.h5.journal").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir / "out.csv").c_str(), 0600), 0);
  alarm(20);  // a regression blocks: end it with a signal rather than hang the suite
  EXPECT_NE(refusal([&] { LogReader r(dir / "c.h5.journal"); }).find("is a FIFO, not a regular file"), std::string::npos);
  EXPECT_NE(refusal([&] { (void)open_regular_to_read(dir / "c.h5.journal"); }).find("is a FIFO"), std::string::npos);
  // An output that is a FIFO no process reads: refused, not waited on.
  EXPECT_NE(refusal([&] { OutputFile out(dir / "out.csv", {}, true); }).find("is a FIFO that no process reads"),
            std::string::npos);
  alarm(0);
}

TEST(Sidecar, ASparseRecordIsNotChecksummedByteByByte) {
  const auto dir = test::scratch_dir("sidecar_sparse");
  const auto journal = dir / "c.h5.journal";
  {
    LogWriter w(journal, 0);
    w.add(1, "header");
    w.sync();
  }
  const auto whole = fs::file_size(journal);
  {
    std::ofstream out(journal, std::ios::app | std::ios::binary);
    std::string frame;
    append_le(frame, 2, 4);
    append_le(frame, std::uint64_t{64} << 30, 8);  // 64 GiB, which the file "has" as a hole
    out << frame;
  }
  fs::resize_file(journal, whole + 12 + (std::uint64_t{64} << 30) + 4);
  const auto start = std::chrono::steady_clock::now();
  const LogReader read(journal);
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(read.records().size(), 1u);  // the header; the sparse record is a damaged tail
  EXPECT_EQ(read.valid_bytes(), whole);
  EXPECT_LT(took_s, 10.0) << "64 GiB of holes were read";  // reading them took minutes
}

TEST(Sidecar, AnOutputStoppedBySigtermLeavesNoTemporary) {
  const auto dir = test::scratch_dir("sidecar_sigterm");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_temporaries_on_signals();
    OutputFile out(dir / "history.csv", {}, false);
    out.stream() << std::string(1 << 20, 'x');  // beyond the buffer: in the temporary
    (void)!::write(ready[1], "x", 1);
    for (;;) ::pause();
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  int hidden = 0;
  for (const auto& e : fs::directory_iterator(dir)) hidden += e.path().filename().string().front() == '.';
  EXPECT_EQ(hidden, 1) << "the temporary is there while the output is written";
  ::kill(child, SIGTERM);
  int wstatus = 0;
  ASSERT_EQ(::waitpid(child, &wstatus, 0), child);
  EXPECT_TRUE(WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGTERM);
  EXPECT_TRUE(fs::is_empty(dir)) << "a temporary was left behind";
  ::close(ready[0]);
  ::close(ready[1]);
}

}  // namespace
}  // namespace pcrf::io
