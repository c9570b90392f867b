// Fuzz target: the deck reader that finds the cards verify refuses. Besides
// crashes, it checks that each finding names a line of the deck.
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
  return 0;
}
