// The deck reader: the cards of an edited deck that make ngspice run commands
// or read other files, and verify's refusal of them.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
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
