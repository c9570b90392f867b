#include "spice/deck_reader.h"

#include <cctype>

#include "common/error.h"

namespace gearpatch::spice {
namespace {

bool starts_with_nocase(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) return false;
  return true;
}

std::string_view trim_front(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  return s;
}

/// The card for a message: printable, without trailing blanks, at most 60 bytes.
std::string shown(std::string_view card) {
  while (!card.empty() && std::isspace(static_cast<unsigned char>(card.back()))) card.remove_suffix(1);
  std::string out;
  for (char ch : card.substr(0, 60)) out += std::isprint(static_cast<unsigned char>(ch)) ? ch : '?';
  return card.size() > 60 ? out + "..." : out;
}

/// What ngspice does with one physical line beyond simulating, or empty.
/// `raw` is the line as written, `first` says whether it is the title line.
std::string_view what_it_does(std::string_view raw, bool first) {
  if (first && starts_with_nocase(raw, "*ng_script"))
    return "a *ng_script deck is a list of ngspice commands (shell included)";
  std::string_view card = trim_front(raw);
  if (card.substr(0, 2) == "*#") return "a *# line runs an ngspice command (shell included)";
  if (!card.empty() && card.front() == '+') card = trim_front(card.substr(1));
  if (starts_with_nocase(card, ".control"))
    return "a .control block runs ngspice commands (shell included)";
  if (starts_with_nocase(card, ".inc") || starts_with_nocase(card, ".lib"))
    return "it reads another file, which may hold .control blocks";
  return {};
}

}  // namespace

std::vector<DeckCommand> find_deck_commands(std::string_view deck) {
  std::vector<DeckCommand> found;
  if (deck.substr(0, 3) == "\xEF\xBB\xBF") deck.remove_prefix(3);  // a UTF-8 byte-order mark
  std::size_t number = 0;
  while (!deck.empty()) {
    const std::size_t end = deck.find('\n');
    const std::string_view raw = deck.substr(0, end);
    deck.remove_prefix(end == std::string_view::npos ? deck.size() : end + 1);
    ++number;
    if (std::string_view what = what_it_does(raw, number == 1); !what.empty())
      found.push_back({number, shown(trim_front(raw)), std::string(what)});
  }
  return found;
}

void refuse_deck_commands(std::string_view deck, const std::string& path) {
  const auto commands = find_deck_commands(deck);
  if (commands.empty()) return;
  const DeckCommand& c = commands.front();
  throw Error(path + ":" + std::to_string(c.line) + ": " + c.card + ": " + c.what +
              "; ngspice would run the deck as written (pass --allow-control if you trust it)");
}

}  // namespace gearpatch::spice
