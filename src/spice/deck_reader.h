#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace gearpatch::spice {

/// A card of a deck that makes ngspice do more than simulate the circuit:
/// run front-end commands (`.control` … `.endc`, `*#` lines, a `*ng_script`
/// file), which include `shell`, or read another file (`.include`, `.lib`)
/// that may hold such commands.
struct DeckCommand {
  std::size_t line = 0;  ///< 1-based line where the card starts
  std::string card;      ///< the card as written, trimmed and shortened
  std::string what;      ///< what ngspice does with it
};

/// Every such card of a deck, in order. Reads as ngspice does: case-insensitive,
/// cards by prefix (`.controls` is `.control`), leading whitespace ignored; a
/// `+` continuation line is checked as a card too, since one without a card
/// before it stands alone.
std::vector<DeckCommand> find_deck_commands(std::string_view deck);

/// Throws gearpatch::Error (input) naming `path`, the line and the card if
/// the deck holds any of the cards above: verify runs a deck as written.
void refuse_deck_commands(std::string_view deck, const std::string& path);

}  // namespace gearpatch::spice
