// Every command that writes a file follows the one output rule (io::OutputFile): it never
// writes over its input, whatever name the output gives it (path, symbolic link, hard link)
// and even with --overwrite; it replaces an existing file only with --overwrite; files get
// the user's umask. Every write is checked: a full disk or a full stdout ends the command
// with one line naming the target and exit code 2; a closed pipe ends it quietly.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

using study_test::pcrf;
using study_test::quoted;
namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

bool have_matplotlib() {
  return test::run_command(std::string("'") + PCRF_PYTHON + "' -c 'import matplotlib, numpy'").exit_code == 0;
}

/// A small grid cube in `dir` (c.h5, from c.toml), and a record file (rec.txt).
void make_cube(const fs::path& dir) {
  test::write_file(dir, "c.toml", study_test::small_grid_study());
  const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study c.toml -o c.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string record;
  for (int i = 0; i < 400; ++i) record += std::to_string(0.3 * (i % 7 - 3)) + "\n";
  test::write_file(dir, "rec.txt", record);
}

/// `pcrf ARGS` in `dir`.
test::CommandResult in(const fs::path& dir, const std::string& args) {
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " " + args);
}

const std::string kRun = "run --record rec.txt --format one-column --dt 0.01";

TEST(OutputRule, NoCommandWritesOverItsInputWhateverTheOutputIsCalled) {
  const auto dir = test::scratch_dir("output_rule_inputs");
  make_cube(dir);
  fs::create_symlink("c.h5", dir / "link.h5");
  fs::create_hard_link(dir / "c.h5", dir / "hard.h5");
  fs::create_symlink("rec.txt", dir / "rec_link.csv");
  fs::create_symlink("c.h5", dir / "cube_link.svg");
  const std::string cube = read(dir / "c.h5"), record = read(dir / "rec.txt");
  std::vector<std::string> commands;
  for (const std::string name : {"c.h5", "link.h5", "hard.h5", "./c.h5"}) {
    commands.push_back("cube export c.h5 -o " + name);
    commands.push_back("cube fragility c.h5 --csv " + name);
    commands.push_back("cube fragility c.h5 --points " + name);
    commands.push_back("cube sensitivity c.h5 -m theta_max_rad --csv " + name);
    commands.push_back("cube merge c.h5 -o " + name);
  }
  commands.push_back(kRun + " --history rec.txt");
  commands.push_back(kRun + " --history rec_link.csv");
  if (have_matplotlib()) commands.push_back("plot sweep cube_link.svg -o cube_link.svg");
  for (const auto& command : commands)
    for (const std::string overwrite : {"", " --overwrite"}) {
      const auto r = in(dir, command + overwrite);
      EXPECT_EQ(r.exit_code, 2) << command << overwrite << "\n" << r.err;
      EXPECT_NE(r.err.find("the input"), std::string::npos) << command << overwrite << "\n" << r.err;
      EXPECT_NE(r.err.find("--overwrite does not apply to inputs"), std::string::npos) << r.err;
      EXPECT_EQ(lines(r.err), 1) << command << overwrite << "\n" << r.err;
    }
  EXPECT_EQ(read(dir / "c.h5"), cube);
  EXPECT_EQ(read(dir / "rec.txt"), record);
  // --csv and --points of one command are not the same file either.
  const auto both = in(dir, "cube fragility c.h5 --csv t.csv --points t.csv");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("t.csv: is the input"), std::string::npos) << both.err;
  EXPECT_FALSE(fs::exists(dir / "t.csv"));
}

TEST(OutputRule, AnExistingFileIsReplacedOnlyWithOverwrite) {
  const auto dir = test::scratch_dir("output_rule_existing");
  make_cube(dir);
  ASSERT_EQ(in(dir, "study c.toml -o d.h5 --shard 1/2 --progress-interval 0").exit_code, 0);
  ASSERT_EQ(in(dir, "study c.toml -o e.h5 --shard 2/2 --progress-interval 0").exit_code, 0);
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"cube export c.h5 -o out.csv", "out.csv"},
      {"cube export c.h5 --history none -o out.csv", "out.csv"},
      {kRun + " --history out.csv", "out.csv"},
      {"cube merge d.h5 e.h5 -o out.h5", "out.h5"},
  };
  for (const auto& [command, output] : commands) {
    test::write_file(dir, output, "keep me");
    const auto refused = in(dir, command);
    EXPECT_EQ(refused.exit_code, 2) << command << "\n" << refused.err;
    EXPECT_NE(refused.err.find(output + ": already exists; use --overwrite to replace it"), std::string::npos) << refused.err;
    EXPECT_EQ(read(dir / output), "keep me") << command;
    if (command.find("--history none") != std::string::npos) continue;  // refused before the cube is read
    const auto replaced = in(dir, command + " --overwrite");
    EXPECT_EQ(replaced.exit_code, 0) << command << "\n" << replaced.err;
    EXPECT_NE(read(dir / output), "keep me") << command;
  }
  // A failure after the check (no such history) leaves the old file as it was.
  test::write_file(dir, "out.csv", "keep me");
  EXPECT_EQ(in(dir, "cube export c.h5 --history none -o out.csv --overwrite").exit_code, 2);
  EXPECT_EQ(read(dir / "out.csv"), "keep me");
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
}

TEST(OutputRule, FilesGetTheUsersUmask) {
  const auto dir = test::scratch_dir("output_rule_umask");
  make_cube(dir);
  for (const std::string mask : {"022", "027"}) {
    const mode_t expected = 0666 & ~static_cast<mode_t>(std::stoi(mask, nullptr, 8));
    std::vector<std::pair<std::string, std::string>> commands = {
        {"cube export c.h5 -o t" + mask + ".csv", "t" + mask + ".csv"},
        {kRun + " --history h" + mask + ".csv", "h" + mask + ".csv"},
        {"study c.toml -o s" + mask + ".h5 --progress-interval 0", "s" + mask + ".h5"},
    };
    if (have_matplotlib()) commands.push_back({"plot sweep c.h5 -o f" + mask + ".png", "f" + mask + ".png"});
    for (const auto& [command, output] : commands) {
      const auto r = test::run_command("cd " + quoted(dir) + " && umask " + mask + " && " + pcrf() + " " + command);
      ASSERT_EQ(r.exit_code, 0) << command << "\n" << r.err;
      struct stat st {};
      ASSERT_EQ(::stat((dir / output).c_str(), &st), 0) << output;
      EXPECT_EQ(st.st_mode & 0777, expected) << command;
    }
  }
}

TEST(OutputRule, AFullStdoutIsAnErrorAndAClosedPipeEndsQuietly) {
  const auto dir = test::scratch_dir("output_rule_stdout");
  make_cube(dir);
  for (const std::string& command : std::vector<std::string>{kRun, "record rec.txt --format one-column --dt 0.01", "cube info c.h5", "cube export c.h5", "--help"}) {
    const auto full = in(dir, command + " > /dev/full");
    EXPECT_EQ(full.exit_code, 2) << command << "\n" << full.err;
    EXPECT_EQ(full.err, "pcrf: error: standard output: cannot write: No space left on device\n") << command;
    // The reader is gone before the first write: SIGPIPE, or EPIPE when it is ignored.
    for (const std::string pipe : {"", "trap '' PIPE; "}) {
      const auto closed = test::run_command("cd " + quoted(dir) + " && " + pipe + "{ sleep 0.2; " + pcrf() + " " + command +
                                            "; echo status=$? >&2; } | true");
      EXPECT_EQ(closed.err, "status=141\n") << pipe << command;
    }
  }
}

TEST(OutputRule, AFullDiskEndsEveryWriterWithOneLineNamingTheFile) {
  const auto dir = test::scratch_dir("output_rule_full_disk");
  make_cube(dir);
  ASSERT_EQ(in(dir, "study c.toml -o d.h5 --shard 1/2 --progress-interval 0").exit_code, 0);
  ASSERT_EQ(in(dir, "study c.toml -o e.h5 --shard 2/2 --progress-interval 0").exit_code, 0);
  const auto small = dir / "small";
  fs::create_directories(small);
  ::umount(small.c_str());
  if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=16k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  struct Unmount {
    fs::path at;
    ~Unmount() { ::umount(at.c_str()); }
  } unmount{small};
  test::write_file(small, "filler", std::string(12 * 1024, 'f'));  // leaves less than any output needs
  std::vector<std::pair<std::string, std::string>> commands = {
      {"cube export c.h5 -o small/t.csv", "small/t.csv"},
      {kRun + " --history small/h.csv", "small/h.csv"},
      {"cube merge d.h5 e.h5 -o small/m.h5", "small/m.h5"},
  };
  if (have_matplotlib()) commands.push_back({"plot sweep c.h5 -o small/f.png", "small/f.png"});
  for (const auto& [command, output] : commands) {
    const auto r = in(dir, command);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(output), std::string::npos) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << command << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / output)) << command;
  }
  for (const auto& e : fs::directory_iterator(small)) EXPECT_EQ(e.path().filename(), "filler") << e.path();
}

}  // namespace
}  // namespace pcrf
