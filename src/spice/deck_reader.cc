#include "spice/deck_reader.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <map>

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

namespace {

constexpr std::string_view kHeaderStart = "* gearpatch deck:";

/// The key=value words after the header's start; a word without '=' is kept with an empty value.
std::map<std::string, std::string> header_words(std::string_view text) {
  std::map<std::string, std::string> words;
  while (!(text = trim_front(text)).empty()) {
    std::size_t end = 0;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    const std::string_view word = text.substr(0, end);
    const std::size_t equals = word.find('=');
    words[std::string(word.substr(0, equals))] =
        equals == std::string_view::npos ? "" : std::string(word.substr(equals + 1));
    text.remove_prefix(end);
  }
  return words;
}

}  // namespace

std::string format_deck_header(const DeckHeader& h) {
  return fmt::format("{} level={} scaling={} beta={} unit={} k0={} quality={}\n", kHeaderStart, h.level,
                     h.scaling, h.beta, h.unit_volts, h.integrator_constant, h.quality);
}

std::optional<DeckHeader> read_deck_header(std::string_view deck, const std::string& path) {
  std::size_t number = 0;
  std::string_view raw;
  while (!deck.empty()) {
    const std::size_t end = deck.find('\n');
    raw = deck.substr(0, end);
    deck.remove_prefix(end == std::string_view::npos ? deck.size() : end + 1);
    ++number;
    if (raw.substr(0, kHeaderStart.size()) == kHeaderStart) break;
    raw = {};
  }
  if (raw.empty()) return std::nullopt;
  if (raw.back() == '\r') raw.remove_suffix(1);
  auto words = header_words(raw.substr(kHeaderStart.size()));
  const auto fail = [&](const std::string& key, const std::string& problem) -> Error {
    return Error(fmt::format("{}:{}: {}: {} (the deck's gearpatch header)", path, number, key, problem));
  };
  const auto word = [&](const std::string& key) {
    const auto found = words.find(key);
    if (found == words.end() || found->second.empty()) throw fail(key, "missing");
    return shown(found->second);
  };
  const auto one_of = [&](const std::string& key, std::string_view a, std::string_view b) {
    const std::string value = word(key);
    if (value != a && value != b) throw fail(key, fmt::format("{}: must be {} or {}", value, a, b));
    return value;
  };
  const auto positive = [&](const std::string& key) {
    const std::string value = word(key);
    char* end = nullptr;
    const double x = std::strtod(value.c_str(), &end);
    if (end != value.c_str() + value.size() || !std::isfinite(x) || !(x > 0))
      throw fail(key, value + ": must be a finite number > 0");
    return x;
  };
  DeckHeader h;
  h.level = one_of("level", "ideal", "hardware");
  h.scaling = word("scaling");
  if (h.scaling != "paper" && h.scaling != "autoscale" && h.scaling != "solved" && h.scaling != "solved-autoscale")
    throw fail("scaling", h.scaling + ": must be solved, solved-autoscale, paper or autoscale");
  h.beta = positive("beta");
  h.unit_volts = positive("unit");
  h.integrator_constant = positive("k0");
  h.quality = word("quality");
  h.line = number;
  return h;
}

}  // namespace gearpatch::spice
