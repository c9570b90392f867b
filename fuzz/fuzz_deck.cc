// Fuzz target: the deck reader that finds the cards verify refuses, and the
// header verify --deck holds to. Besides crashes, it checks that each finding
// and a header read name a line of the deck.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/error.h"
#include "spice/deck_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view deck(reinterpret_cast<const char*>(data), size);
  const auto lines = static_cast<std::size_t>(std::count(deck.begin(), deck.end(), '\n')) + 1;
  const auto found = gearpatch::spice::find_deck_commands(deck);
  for (const auto& command : found)
    if (command.line == 0 || command.line > lines) __builtin_trap();
  try {
    gearpatch::spice::refuse_deck_commands(deck, "fuzz.cir");
    if (!found.empty()) __builtin_trap();  // refused exactly when something was found
  } catch (const gearpatch::Error&) {
    if (found.empty()) __builtin_trap();
  }
  try {
    const auto header = gearpatch::spice::read_deck_header(deck, "fuzz.cir");
    if (header && (header->line == 0 || header->line > lines || !(header->beta > 0))) __builtin_trap();
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
