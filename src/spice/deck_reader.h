#pragma once
#include <optional>
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

/// How a deck that gearpatch wrote was made, from its header line, a comment
/// to ngspice: `* gearpatch deck: level=hardware scaling=paper beta=1 unit=10
/// k0=1 quality=normal`. verify --deck holds its options to it, since the
/// deck's numbers mean nothing under another level or scaling.
struct DeckHeader {
  std::string level = "ideal";    ///< ideal or hardware
  /// solved, solved-autoscale (the constraint problem, from the a-priori or the
  /// simulated peak bounds), paper or autoscale (the paper's recipe, a-priori or
  /// from the simulated peaks: the words of decks written before the solver)
  std::string scaling = "solved";
  double beta = 1;                ///< machine time = β · real time
  double unit_volts = 10;         ///< volts per machine unit
  double integrator_constant = 1; ///< k0, 1/s
  std::string quality = "normal"; ///< the --quality preset, or custom
  std::size_t line = 0;           ///< 1-based line of the header in the deck read
};

/// The header line, newline included.
std::string format_deck_header(const DeckHeader& header);

/// The first header line of a deck, or none for a deck without one (a
/// person's own). Throws Error "path:line: key: problem" for a header line
/// that lacks a key or holds a bad value.
std::optional<DeckHeader> read_deck_header(std::string_view deck, const std::string& path);

}  // namespace gearpatch::spice
