// The command line alike in every command: --tolerance with its unit, -o/--out
// and --json FILE with - for stdout, --version, and the examples every --help
// ends with (run here as written).
#include <catch2/catch.hpp>

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "common/atomic_file.h"
#include "support.h"

namespace fs = std::filesystem;
using namespace gearpatch;

namespace {

const std::string kBinary = GEARPATCH_BINARY;

/// A fresh folder that sees the example scenes as scenes/, removed afterwards.
struct WorkDir : testing::TempFolder {
  WorkDir() : TempFolder("cli") {
    fs::create_directory_symlink(testing::source_path("scenes"), path / "scenes");
    fs::create_directory_symlink(testing::source_path("machines"), path / "machines");
  }
  /// Runs `arguments` with the binary from this folder.
  int run(const std::string& arguments, std::string& output) const {
    return testing::run_command("cd " + path.string() + " && " + kBinary + " " + arguments, output);
  }
};

/// The lines after "examples:" in a help text, each without its indent.
std::vector<std::string> examples_of(const std::string& help) {
  std::vector<std::string> examples;
  const auto at = help.find("\nexamples:\n");
  if (at == std::string::npos) return examples;
  std::istringstream lines(help.substr(at + 11));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("  gearpatch ", 0) == 0) examples.push_back(line.substr(2));
  return examples;
}

/// An example as the shell runs it, each of its commands ("gearpatch patch …
/// && gearpatch verify …") by the binary under test.
std::string with_binary(std::string command) {
  command.replace(0, std::string("gearpatch ").size(), kBinary + " ");
  const std::string next = " && gearpatch ";
  for (auto at = command.find(next); at != std::string::npos; at = command.find(next, at + 1))
    command.replace(at, next.size(), " && " + kBinary + " ");
  return command;
}

/// The commands `gearpatch --help` lists.
std::vector<std::string> commands_of(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help.substr(help.find("\ncommands:\n") + 11));
  for (std::string line; std::getline(lines, line) && line.rfind("  ", 0) == 0;)
    names.push_back(line.substr(2, line.find(' ', 2) - 2));
  return names;
}

/// The files and folders an example names as its outputs (the values of the output options).
std::vector<std::string> outputs_of(const std::string& example) {
  static const std::vector<std::string> output_options = {
      "-o", "--out", "--json", "--plot", "--csv", "--figures-plot", "--markdown", "--events",
      "--picture", "--dot", "--keep-deck", "--summary", "--job-list", "--run-dir"};
  std::vector<std::string> outputs;
  std::istringstream words(example);
  for (std::string word, value; words >> word;)
    if (std::find(output_options.begin(), output_options.end(), word) != output_options.end() && words >> value &&
        value != "-")
      outputs.push_back(value);
  return outputs;
}

}  // namespace

TEST_CASE("--tolerance is a percentage with its unit; a bare number is refused", "[common][cli]") {
  WorkDir dir;
  std::string output;
  // 5 once meant 500 % and passed anything; 0.5 meant 50 %.
  for (const char* bare : {"5", "0.5", "0.005"}) {
    INFO(bare);
    CHECK(dir.run(std::string("verify scenes/bild5a.ini --tolerance ") + bare, output) == 2);
    CHECK_THAT(output, Catch::Contains("the unit is missing") && Catch::Contains("--tolerance 0.5%"));
    CHECK_THAT(output, !Catch::Contains("running ngspice"));
  }
  CHECK(dir.run("verify scenes/bild5a.ini --tolerance 500%", output) == 2);
  CHECK_THAT(output, Catch::Contains("--tolerance 500%: must be a finite percentage in (0%, 100%]"));
  CHECK(dir.run("verify scenes/bild5a.ini --tolerance x%", output) == 2);
  CHECK_THAT(output, Catch::Contains("--tolerance x%: not a number"));
  // Written with its unit it is taken as a fraction of full scale: the report says 1 %.
  CHECK(dir.run("verify scenes/bild5a.ini --tolerance 1% --json -", output) == 0);
  CHECK_THAT(output, Catch::Contains("tolerance 1 % of full scale"));
  CHECK(!fs::exists(dir.path / "-"));
}

TEST_CASE("settings takes --json FILE and -o FILE like the other commands; - is stdout", "[common][cli]") {
  WorkDir dir;
  std::string output;
  REQUIRE(dir.run("settings scenes/bild5b.ini --json s.json -o s.txt", output) == 0);
  const auto settings = nlohmann::json::parse(read_file((dir.path / "s.json").string()));
  CHECK(settings.contains("peaks"));
  CHECK_THAT(read_file((dir.path / "s.txt").string()), Catch::Contains("alpha"));
  // --json -: stdout holds only the JSON (the table goes to stderr) and no file named "-" appears.
  REQUIRE(testing::run_command("(cd " + dir.path.string() + " && " + kBinary +
                                   " settings scenes/bild5b.ini --json - > stdout.txt)",
                               output) == 0);
  CHECK(nlohmann::json::parse(read_file((dir.path / "stdout.txt").string())) == settings);
  CHECK_THAT(output, Catch::Contains("alpha"));  // the table, on stderr
  for (const std::string command : {"settings scenes/bild5b.ini -o -", "simulate scenes/bild5b.ini -o - --dt 0.1",
                                    "netlist scenes/bild5b.ini -o -",
                                    "reduce scenes/stages/drive_train.ini --json -"})
    CHECK(dir.run(command, output) == 0);
  CHECK(!fs::exists(dir.path / "-"));
  // Two outputs cannot share stdout.
  CHECK(dir.run("simulate scenes/bild5b.ini --events -", output) == 2);
  CHECK_THAT(output, Catch::Contains("--events -: the same file as --out"));
  CHECK(dir.run("verify scenes/bild5b.ini --json - --keep-deck -", output) == 2);
  CHECK_THAT(output, Catch::Contains("--keep-deck -: the same file as --json") && !Catch::Contains("running ngspice"));
}

TEST_CASE("gearpatch --version prints the project's version", "[common][cli]") {
  std::string output;
  CHECK(testing::run_command(kBinary + " --version", output) == 0);
  CHECK(output == std::string("gearpatch ") + GEARPATCH_VERSION + "\n");
}

TEST_CASE("every --help ends with examples that run as written and make the files they name",
          "[common][cli][ngspice][slow]") {
  WorkDir dir;
  std::string help;
  REQUIRE(dir.run("--help", help) == 0);
  std::vector<std::string> commands = {""};
  for (const std::string& name : commands_of(help)) commands.push_back(name);
  for (const char* name : {"simulate", "settings", "netlist", "verify", "patch", "sweep", "merge", "random-scenes"})
    CHECK(std::find(commands.begin(), commands.end(), name) != commands.end());
  for (const std::string& command : commands) {
    INFO("gearpatch " << command << " --help");
    REQUIRE(dir.run(command + " --help", help) == 0);
    const auto examples = examples_of(help);
    CHECK(!examples.empty());
    CHECK(help.substr(help.rfind("\nexamples:\n")).find("\n\n", 1) == std::string::npos);  // it ends the help
    const bool merged = std::any_of(examples.begin(), examples.end(),
                                    [](const std::string& e) { return e.rfind("gearpatch merge ", 0) == 0; });
    for (const std::string& example : examples) {
      INFO(example);
      std::string output;
      const auto job_list = example.find("--job-list ");
      if (job_list != std::string::npos) fs::remove_all(dir.path / outputs_of(example.substr(job_list)).front());
      const int status =
          testing::run_command("cd " + dir.path.string() + " && (" + with_binary(example) + ") 2>&1", output);
      INFO(output);
      CHECK(status == 0);
      for (const std::string& file : outputs_of(example)) CHECK(fs::exists(dir.path / file));
      if (merged && job_list != std::string::npos)  // the help's GNU Parallel line, on this machine
        CHECK(testing::run_command("cd " + dir.path.string() + " && parallel --will-cite -S : < " +
                                       outputs_of(example.substr(job_list)).front() + "/jobs.txt",
                                   output) == 0);
    }
  }
  // the sheet-runs path: a sheet written by patch, run by verify --patch
  REQUIRE(dir.run("patch --help", help) == 0);
  bool sheet_run = false;
  for (const std::string& example : examples_of(help))
    sheet_run = sheet_run || (example.find("--json") != std::string::npos &&
                              example.find("&& gearpatch verify") != std::string::npos &&
                              example.find("--patch") != std::string::npos);
  CHECK(sheet_run);
}
