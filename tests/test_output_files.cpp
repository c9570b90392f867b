// Tests of output files (common/atomic_file.h, output_set.h) and of the
// commands' outputs: what is refused, what is replaced, modes, links, and
// that one command's outputs land together or not at all.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/output_set.h"
#include "support.h"

namespace fs = std::filesystem;
using namespace gearpatch;

namespace {

struct TestDir : testing::TempFolder {
  TestDir() : TempFolder("out") {}
  /// The names in the folder, sorted: temporaries would show here.
  std::string listing() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(path)) names.insert(e.path().filename().string());
    std::string out;
    for (const auto& n : names) out += n + " ";
    return out;
  }
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  REQUIRE(::stat(path.c_str(), &st) == 0);
  return st.st_mode & 07777;
}

const std::string kBinary = GEARPATCH_BINARY;

}  // namespace

TEST_CASE("outputs refuse FIFOs, directories and devices, and leave them as they were", "[common]") {
  TestDir dir;
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  fs::create_directory(dir / "folder");
  CHECK_THROWS_WITH(check_output_path(dir / "fifo", "--out"),
                    "--out " + dir / "fifo" + ": is a FIFO, not a regular file; give a file path (or - for stdout)");
  CHECK_THROWS_WITH(check_output_path(dir / "folder", "--json"), Catch::Contains("is a directory"));
  CHECK_THROWS_WITH(write_file_atomically(dir / "fifo", "x"), Catch::Contains("is a FIFO"));

  std::string output;
  const std::string simulate = kBinary + " simulate " + testing::scene_path("bild5a");
  CHECK(testing::run_command(simulate + " --out " + dir / "fifo", output) == 2);
  CHECK_THAT(output, Catch::Contains("--out " + dir / "fifo" + ": is a FIFO"));
  CHECK(fs::is_fifo(dir / "fifo"));
  CHECK(testing::run_command(simulate + " --events " + dir / "folder", output) == 2);
  CHECK_THAT(output, Catch::Contains("--events " + dir / "folder" + ": is a directory"));
  CHECK(fs::is_directory(dir / "folder"));
  CHECK(testing::run_command(kBinary + " settings " + testing::scene_path("bild5a") + " -o " + dir / "fifo", output) == 2);
  CHECK(testing::run_command(kBinary + " netlist " + testing::scene_path("bild5a") + " -o " + dir / "folder", output) == 2);
  CHECK(testing::run_command(kBinary + " reduce " + testing::source_path("scenes/stages/drive_train.ini") + " --json " +
                                 dir / "fifo",
                             output) == 2);
  CHECK(testing::run_command(kBinary + " bench " + testing::scene_path("bild5a") + " --only level --json " + dir / "b.json" +
                                 " --markdown " + dir / "fifo",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("--markdown " + dir / "fifo" + ": is a FIFO") && !Catch::Contains("ngspice"));
  CHECK(fs::is_fifo(dir / "fifo"));
  CHECK(dir.listing() == "fifo folder ");

  // A device is refused before anything is written, so this leaves /dev/null alone.
  struct stat before {}, after {};
  REQUIRE(::stat("/dev/null", &before) == 0);
  REQUIRE(S_ISCHR(before.st_mode));
  CHECK(testing::run_command(simulate + " --out /dev/null", output) == 2);
  CHECK_THAT(output, Catch::Contains("--out /dev/null: is a device"));
  REQUIRE(::stat("/dev/null", &after) == 0);
  CHECK(S_ISCHR(after.st_mode));
  CHECK(after.st_rdev == before.st_rdev);
}

TEST_CASE("a new output honours the umask, a replaced one keeps its mode", "[common]") {
  TestDir dir;
  const mode_t old_mask = ::umask(027);
  write_file_atomically(dir / "new.txt", "one\n");
  ::umask(old_mask);
  CHECK(mode_of(dir / "new.txt") == 0640);
  CHECK(slurp(dir / "new.txt") == "one\n");
  fs::permissions(dir / "new.txt", fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read);
  write_file_atomically(dir / "new.txt", "two\n");
  CHECK(mode_of(dir / "new.txt") == 0604);
  CHECK(slurp(dir / "new.txt") == "two\n");
  CHECK(dir.listing() == "new.txt ");
}

TEST_CASE("an output through a symbolic link writes the file it points to and keeps the link", "[common]") {
  TestDir dir;
  fs::create_directory(dir / "real");
  write_file_atomically(dir / "real/data.csv", "old\n");
  fs::create_symlink("real/data.csv", dir / "link.csv");
  CHECK(check_output_path(dir / "link.csv") == dir / "real/data.csv");
  write_file_atomically(dir / "link.csv", "new\n");
  CHECK(fs::is_symlink(dir / "link.csv"));
  CHECK(slurp(dir / "real/data.csv") == "new\n");
  // A dangling link: its target is made.
  fs::create_symlink("real/made.csv", dir / "dangling.csv");
  write_file_atomically(dir / "dangling.csv", "made\n");
  CHECK(fs::is_symlink(dir / "dangling.csv"));
  CHECK(slurp(dir / "real/made.csv") == "made\n");
  // A link to a FIFO is refused like the FIFO.
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  fs::create_symlink("fifo", dir / "to-fifo");
  CHECK_THROWS_WITH(write_file_atomically(dir / "to-fifo", "x"), Catch::Contains("is a FIFO"));
}

TEST_CASE("a missing or unwritable folder is named at once", "[common]") {
  TestDir dir;
  CHECK_THROWS_WITH(check_output_path(dir / "nope/x.csv", "--out"),
                    "--out " + dir / "nope/x.csv" + ": folder " + dir / "nope" + " does not exist");
  CHECK_THROWS_WITH(check_output_path("", "--out"), "--out '': empty file name");
  CHECK(check_output_path("-") == "-");
}

TEST_CASE("an output set lands all its files or none", "[common]") {
  TestDir dir;
  {
    OutputSet outputs;
    outputs.add("--out", dir / "a.csv");
    outputs.add("--events", dir / "b.csv");
    outputs.stage("--out", "a\n");
    CHECK(dir.listing().find(".a.csv.") != std::string::npos);  // staged beside its target
    // The command fails before commit().
  }
  CHECK(dir.listing() == "");
  {
    OutputSet outputs;
    outputs.add("--out", dir / "a.csv");
    outputs.add("--events", dir / "b.csv");
    outputs.stage("--out", "a\n");
    outputs.stage("--events", "b\n");
    REQUIRE(::mkfifo((dir / "b.csv").c_str(), 0600) == 0);  // turned into a FIFO meanwhile
    CHECK_THROWS_WITH(outputs.commit(), Catch::Contains("--events") && Catch::Contains("is a FIFO"));
  }
  CHECK(dir.listing() == "b.csv ");
  fs::remove(dir / "b.csv");
  OutputSet outputs;
  outputs.add("--out", dir / "a.csv");
  CHECK_THROWS_WITH(outputs.add("--events", dir / "./a.csv"), "--events " + dir / "./a.csv" + ": the same file as --out");
  outputs.stage("--out", "a\n");
  outputs.commit();
  CHECK(slurp(dir / "a.csv") == "a\n");
  CHECK(dir.listing() == "a.csv ");
}

TEST_CASE("a command whose later output fails leaves none of its outputs", "[common]") {
  TestDir dir;
  std::string output;
  // simulate: --events into a missing folder is refused before the run; no --out CSV.
  CHECK(testing::run_command(kBinary + " simulate " + testing::scene_path("bild5a") + " --out " + dir / "a.csv" + " --events " +
                                 dir / "nope/e.csv",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("--events " + dir / "nope/e.csv" + ": folder"));
  CHECK(dir.listing() == "");
  // "-" writes through to stdout.
  CHECK(testing::run_command(kBinary + " simulate " + testing::scene_path("bild5a") + " --out - --events " + dir / "e.csv",
                             output) == 0);
  CHECK_THAT(output, Catch::StartsWith("t,omega_p,omega_s,dphi,m0,event\n"));
  CHECK(dir.listing() == "e.csv ");
}

TEST_CASE("verify checks its outputs before the run and keeps its verdict when the plot fails late", "[common]") {
  TestDir dir;
  std::string output;
  const std::string verify = kBinary + " verify " + testing::scene_path("bild5a");
  // --keep-deck into a missing folder is a bad option, found before ngspice runs.
  CHECK(testing::run_command(verify + " --keep-deck " + dir / "nope/deck.cir", output) == 2);
  CHECK_THAT(output, Catch::Contains("--keep-deck " + dir / "nope/deck.cir" + ": folder"));
  CHECK_THAT(output, !Catch::Contains("running ngspice"));
  // A missing --plot folder is not gnuplot's fault.
  CHECK(testing::run_command(verify + " --plot " + dir / "nope/plot.svg", output) == 2);
  CHECK_THAT(output, Catch::Contains("--plot " + dir / "nope/plot.svg" + ": folder"));
  CHECK_THAT(output, !Catch::Contains("gnuplot") && !Catch::Contains("running ngspice"));
  // No gnuplot at all: said at once.
  fs::create_directory(dir / "bin");
  CHECK(testing::run_command("PATH=" + dir / "bin" + " " + verify + " --plot " + dir / "plot.svg", output) == 2);
  CHECK_THAT(output, Catch::Contains("gnuplot was not found") && !Catch::Contains("running ngspice"));
  // A gnuplot that fails late: a warning after the report; the JSON lands, the status is the verdict's.
  std::ofstream(dir / "bin/gnuplot") << "#!/bin/sh\necho 'fake gnuplot: no luck' >&2\nexit 1\n";
  fs::permissions(dir / "bin/gnuplot", fs::perms::owner_all);
  CHECK(testing::run_command("PATH=" + dir / "bin" + ":$PATH " + verify + " --json " + dir / "report.json" +
                                 " --plot " + dir / "plot.svg",
                             output) == 0);
  CHECK_THAT(output, Catch::Contains("PASS") && Catch::Contains("warning: --plot " + dir / "plot.svg") &&
                         Catch::Contains("gnuplot failed") && Catch::Contains("fake gnuplot: no luck"));
  CHECK(output.find("warning: --plot") > output.find("PASS"));
  CHECK(nlohmann::json::parse(slurp(dir / "report.json"))["passed"] == true);
  CHECK(dir.listing() == "bin report.json ");
}
