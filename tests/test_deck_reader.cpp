// The deck reader: the cards of an edited deck that make ngspice run commands
// or read other files, and verify's refusal of them.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "spice/deck_reader.h"
#include "support.h"

using namespace gearpatch;
namespace fs = std::filesystem;

namespace {

std::vector<std::size_t> lines_of(const std::vector<spice::DeckCommand>& found) {
  std::vector<std::size_t> lines;
  for (const auto& c : found) lines.push_back(c.line);
  return lines;
}

}  // namespace

TEST_CASE("control blocks are found as ngspice finds them", "[spice]") {
  using V = std::vector<std::size_t>;
  CHECK(spice::find_deck_commands(testing::rc_step_deck).empty());
  CHECK(lines_of(spice::find_deck_commands("t\nR1 a 0 1\n.control\nshell rm -rf x\n.endc\n.end\n")) == V{3});
  // case, leading blanks, a prefix (ngspice compares the first letters only), CRLF
  CHECK(lines_of(spice::find_deck_commands("t\r\n  .CONTROL\r\n\t.Controls\r\n.end\r\n")) == V{2, 3});
  // a continuation line is checked too; a comment is not a card
  CHECK(lines_of(spice::find_deck_commands("t\nR1 a 0\n+ .control\n* .control\n.end\n")) == V{3});
  // *# runs a command outside a block; a *ng_script deck is all commands
  CHECK(lines_of(spice::find_deck_commands("t\n*# shell date\n.end\n")) == V{2});
  CHECK(lines_of(spice::find_deck_commands("*NG_SCRIPT\nsource x.cir\n")) == V{1});
  CHECK(lines_of(spice::find_deck_commands("\xEF\xBB\xBF*ng_script\nrun\n")) == V{1});
  // other files may hold control blocks
  CHECK(lines_of(spice::find_deck_commands("t\n.include a.cir\n.INC b\n .lib m.lib tt\n.end\n")) == V{2, 3, 4});
  const auto found = spice::find_deck_commands("t\n.control\n");
  REQUIRE(found.size() == 1);
  CHECK(found[0].card == ".control");
  CHECK_THAT(found[0].what, Catch::Contains("shell"));
}

TEST_CASE("the generated decks hold no commands", "[spice]") {
  for (const auto& entry : fs::directory_iterator(testing::source_path("netlists"))) {
    INFO(entry.path());
    CHECK(spice::find_deck_commands(read_file(entry.path().string())).empty());
  }
}

TEST_CASE("a deck with commands is refused naming file, line and card", "[spice]") {
  CHECK_NOTHROW(spice::refuse_deck_commands(testing::rc_step_deck, "rc.cir"));
  CHECK_THROWS_WITH(spice::refuse_deck_commands("t\n\n  .control\nshell id\n.endc\n", "my.cir"),
                    Catch::StartsWith("my.cir:3: .control: a .control block runs ngspice commands") &&
                        Catch::Contains("--allow-control"));
}

TEST_CASE("verify --deck refuses a control block unless allowed", "[verify][ngspice][cli]") {
  // The generated deck of bild5a with a control block that leaves a mark.
  const fs::path dir = fs::temp_directory_path();
  const std::string deck_file = (dir / "gearpatch-deck-control.cir").string();
  const std::string marker = (dir / "gearpatch-deck-control.ran").string();
  std::string deck = read_file(testing::source_path("netlists/bild5a.ideal.cir"));
  deck.insert(deck.rfind(".end"), ".control\nshell touch " + marker + "\n.endc\n");
  std::ofstream(deck_file) << deck;
  const std::size_t control_line = std::count(deck.begin(), deck.begin() + deck.find(".control"), '\n') + 1;
  fs::remove(marker);

  const std::string verify = std::string(GEARPATCH_BINARY) + " verify " +
                             testing::source_path("scenes/bild5a.ini") + " --deck " + deck_file;
  std::string output;
  CHECK(testing::run_command(verify, output) == 2);
  CHECK_THAT(output, Catch::Contains(deck_file + ":" + std::to_string(control_line) + ": .control"));
  CHECK(!fs::exists(marker));  // ngspice never saw the deck

  CHECK(testing::run_command(verify + " --allow-control", output) == 0);
  CHECK(fs::exists(marker));
  fs::remove(marker);

  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " verify --help", output) == 0);
  CHECK_THAT(output, Catch::Contains("runs it as written") && Catch::Contains("--allow-control"));
}

TEST_CASE("a deck's gearpatch header is read back, and a broken one is refused by line and key", "[spice]") {
  spice::DeckHeader made;
  made.level = "hardware";
  made.scaling = "autoscale";
  made.beta = 0.013;
  made.quality = "fine";
  const std::string line = spice::format_deck_header(made);
  CHECK(line == "* gearpatch deck: level=hardware scaling=autoscale beta=0.013 unit=10 k0=1 quality=fine\n");
  const auto read = spice::read_deck_header("title\n" + line + "R1 a 0 1\n.end\n", "d.cir");
  REQUIRE(read);
  CHECK(read->level == "hardware");
  CHECK(read->scaling == "autoscale");
  CHECK(read->beta == 0.013);
  CHECK(read->quality == "fine");
  CHECK(read->line == 2);
  CHECK(!spice::read_deck_header(testing::rc_step_deck, "rc.cir"));  // a person's own deck
  CHECK_THROWS_WITH(spice::read_deck_header("t\n* gearpatch deck: level=ideal beta=1\n", "d.cir"),
                    Catch::StartsWith("d.cir:2: scaling: missing"));
  CHECK_THROWS_WITH(
      spice::read_deck_header("t\n* gearpatch deck: level=real scaling=paper beta=1 unit=10 k0=1 quality=normal\n",
                              "d.cir"),
      Catch::StartsWith("d.cir:2: level: real: must be ideal or hardware"));
  CHECK_THROWS_WITH(
      spice::read_deck_header("t\n* gearpatch deck: level=ideal scaling=paper beta=nan unit=10 k0=1 quality=normal\n",
                            "d.cir"),
      Catch::StartsWith("d.cir:2: beta: nan: must be a finite number > 0"));
}

TEST_CASE("every committed deck says in its header how it was made", "[spice]") {
  for (const auto& name : testing::example_scenes())
    for (const char* level : {"ideal", "hardware"}) {
      const std::string file = "netlists/" + name + "." + level + ".cir";
      INFO(file);
      const auto header = spice::read_deck_header(read_file(testing::source_path(file)), file);
      REQUIRE(header);
      CHECK(header->level == level);
      CHECK(header->scaling == "solved");
      CHECK(header->quality == "normal");
    }
}

TEST_CASE("verify --deck holds to the deck's header and says when a deck has none", "[verify][ngspice][cli]") {
  const fs::path dir = fs::temp_directory_path();
  const std::string scene = testing::source_path("scenes/bild5a.ini");
  const std::string deck_file = (dir / "gearpatch-deck-header.cir").string();
  const std::string json_file = (dir / "gearpatch-deck-header.json").string();
  const std::string binary = GEARPATCH_BINARY;
  std::string output;
  // The deck verify itself recommends: hardware, scaled from the peaks.
  REQUIRE(testing::run_command(binary + " netlist " + scene + " --level hardware --autoscale -o " + deck_file,
                               output) == 0);
  const std::string verify = binary + " verify " + scene + " --deck " + deck_file;
  // No options: level and scaling come from the deck, and it passes (read as an
  // ideal deck with the paper's scaling, every signal was ~9 % off).
  CHECK(testing::run_command(verify + " --json " + json_file, output) == 0);
  CHECK_THAT(output, Catch::Contains("level hardware") && Catch::Contains("from its gearpatch header"));
  auto report = nlohmann::json::parse(read_file(json_file));
  CHECK(report["level"] == "hardware");
  CHECK(report["scaling"] == "solved-autoscale");
  CHECK(report["deck_scaling"] == "header");
  // An option that contradicts the deck is refused before ngspice runs.
  CHECK(testing::run_command(verify + " --level ideal", output) == 2);
  CHECK_THAT(output, Catch::Contains("--level ideal: --deck " + deck_file + " was written with level=hardware") &&
                         !Catch::Contains("running ngspice"));
  CHECK(testing::run_command(verify + " --quality draft", output) == 2);
  CHECK_THAT(output, Catch::Contains("was written with quality=normal"));
  // A deck with the paper's scaling overloads on hardware: the advice is a new deck, not an option it refuses.
  const std::string paper_file = (dir / "gearpatch-deck-header-paper.cir").string();
  REQUIRE(testing::run_command(binary + " netlist " + scene + " --level hardware --scaling paper -o " + paper_file,
                               output) == 0);
  CHECK(testing::run_command(binary + " verify " + scene + " --deck " + paper_file + " --scaling solved", output) == 2);
  CHECK_THAT(output, Catch::Contains("was written with scaling=paper"));
  CHECK(testing::run_command(binary + " verify " + scene + " --deck " + paper_file, output) == 1);
  CHECK_THAT(output, Catch::Contains("overload") &&
                         Catch::Contains("write the deck again with gearpatch netlist --autoscale"));
  fs::remove(paper_file);
  // Without the header (a person's own deck) the options decide, and the report says so.
  std::string deck = read_file(deck_file);
  const auto at = deck.find("* gearpatch deck:");
  REQUIRE(at != std::string::npos);
  deck.erase(at, deck.find('\n', at) + 1 - at);
  std::ofstream(deck_file, std::ios::trunc) << deck;
  CHECK(testing::run_command(verify + " --level hardware --autoscale --json " + json_file, output) == 0);
  CHECK_THAT(output, Catch::Contains("without a gearpatch header"));
  report = nlohmann::json::parse(read_file(json_file));
  CHECK(report["deck_scaling"] == "options");
  fs::remove(deck_file);
  fs::remove(json_file);
}
