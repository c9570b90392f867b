#include "spice/rawfile.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <optional>

#include <fmt/format.h>

#include "common/error.h"

namespace gearpatch::spice {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(fmt::format("rawfile {}: {}", where, what), Error::Kind::simulator);
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

std::string_view trim(std::string_view s) {
  const auto is_space = [](char ch) { return std::isspace(static_cast<unsigned char>(ch)) != 0; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

/// Quotes file content in a message: short, and printable even if the bytes are not.
std::string quote(std::string_view s) {
  std::string out = "'";
  for (char ch : s.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(ch)) ? ch : '?';
  return out + (s.size() > 40 ? "...'" : "'");
}

std::vector<std::string_view> split_words(std::string_view s) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) words.push_back(s.substr(start, i - start));
  }
  return words;
}

template <typename T>
std::optional<T> parse_number(std::string_view s) {
  T value{};
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return value;
}

/// A read position in the rawfile that knows its line, so that errors can say
/// where they are. Past a binary section line numbers mean nothing, so it then
/// names byte offsets instead.
struct Cursor {
  std::string_view bytes;
  std::size_t pos = 0;
  std::size_t line = 0;        ///< number of the line last returned by next_line
  std::size_t line_start = 0;  ///< byte offset of that line
  bool past_binary = false;

  bool at_end() const { return pos >= bytes.size(); }

  std::string where() const {
    return past_binary ? fmt::format("byte {}", line_start) : fmt::format("line {}", line);
  }

  /// The next line without its terminator; `terminated` says whether a '\n' ended it
  /// (a missing one means the file was cut inside this line).
  std::string_view next_line(bool* terminated = nullptr) {
    line_start = pos;
    std::size_t end = bytes.find('\n', pos);
    bool has_newline = end != std::string_view::npos;
    if (!has_newline) end = bytes.size();
    std::string_view text = bytes.substr(pos, end - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    pos = has_newline ? end + 1 : end;
    ++line;
    if (terminated) *terminated = has_newline;
    return text;
  }

  std::string_view peek_line() const {
    Cursor copy = *this;
    return copy.next_line();
  }
};

/// The header of one plot as far as reading its data needs it.
struct Header {
  Plot plot;
  std::optional<std::size_t> variable_count;
  std::size_t declared_points = 0;  ///< 0 when a run was cut before ngspice patched it
  bool binary = false;
};

std::size_t parse_count(const Cursor& c, std::string_view key, std::string_view value) {
  auto n = parse_number<std::size_t>(trim(value));
  if (!n) fail(c.where(), fmt::format("{} must be a whole number, got {}", key, quote(value)));
  return *n;
}

void check_flags(const Cursor& c, std::string_view flags) {
  for (std::string_view word : split_words(flags)) {
    if (lower(word) == "complex") fail(c.where(), "complex data are not supported (Flags: complex)");
  }
}

void read_variables(Cursor& c, Header& h) {
  if (!h.variable_count) fail(c.where(), "'Variables:' comes before 'No. Variables:'");
  for (std::size_t i = 0; i < *h.variable_count; ++i) {
    if (c.at_end()) fail(c.where(), fmt::format("file ends after {} of {} variables", i, *h.variable_count));
    std::vector<std::string_view> words = split_words(c.next_line());
    if (words.size() < 3 || parse_number<std::size_t>(words[0]) != i) {
      fail(c.where(), fmt::format("expected variable {} as '{}  name  type'", i, i));
    }
    h.plot.variables.push_back({lower(words[1]), std::string(words[2])});
  }
}

/// Applies one "Key: value" header line; returns true at the line that starts
/// the data. Keys ngspice may add in later versions ("Command:") are skipped.
bool apply_header_line(Cursor& c, Header& h, const std::string& key, std::string_view value) {
  if (key == "title") {
    h.plot.title = value;
  } else if (key == "plotname") {
    h.plot.name = value;
  } else if (key == "flags") {
    check_flags(c, value);
    h.plot.flags = value;
  } else if (key == "no. variables") {
    h.variable_count = parse_count(c, "No. Variables", value);
  } else if (key == "no. points") {
    h.declared_points = parse_count(c, "No. Points", value);
    h.plot.declared_points = h.declared_points;
  } else if (key == "variables") {
    read_variables(c, h);
  } else if (key == "binary" || key == "values") {
    if (!h.variable_count) fail(c.where(), "data section before 'No. Variables:'");
    if (*h.variable_count == 0) fail(c.where(), "No. Variables is 0");
    if (h.plot.variables.size() != *h.variable_count) fail(c.where(), "data section before 'Variables:'");
    h.binary = key == "binary";
    return true;
  }
  return false;
}

/// Reads header lines up to and including "Binary:" or "Values:".
Header read_header(Cursor& c) {
  Header h;
  while (!c.at_end()) {
    std::string_view text = c.next_line();
    if (trim(text).empty()) continue;
    std::size_t colon = text.find(':');
    if (colon == std::string_view::npos) fail(c.where(), fmt::format("expected 'Key: value', got {}", quote(text)));
    if (apply_header_line(c, h, lower(trim(text.substr(0, colon))), trim(text.substr(colon + 1)))) return h;
  }
  fail(c.where(), "file ends in a plot header (expected 'Binary:' or 'Values:')");
}

/// Binary data: native-endian float64, point after point. Returns whether
/// another plot may follow (not after a short or undeclared data section).
bool read_binary(Cursor& c, Header& h) {
  const std::size_t width = h.plot.variables.size();
  const std::size_t point_bytes = width * sizeof(double);
  const std::size_t complete = (c.bytes.size() - c.pos) / point_bytes;
  const std::size_t n = h.declared_points == 0 ? complete : std::min(h.declared_points, complete);
  h.plot.columns.assign(width, std::vector<double>(n));
  const char* data = c.bytes.data() + c.pos;
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < width; ++j) {
      std::memcpy(&h.plot.columns[j][k], data + (k * width + j) * sizeof(double), sizeof(double));
    }
  }
  c.pos += n * point_bytes;
  c.past_binary = true;
  return h.declared_points != 0 && n == h.declared_points;
}

/// ASCII data: each point is its index followed by one number per variable,
/// whitespace-separated (ngspice puts one per line). The section ends at the
/// declared count, the next header line, or the end of the file, where an
/// unterminated line and an incomplete point are dropped as cut off.
void read_values(Cursor& c, Header& h) {
  const std::size_t width = h.plot.variables.size();
  h.plot.columns.assign(width, {});
  std::vector<double> point;
  bool have_index = false;
  std::size_t count = 0;
  while (!c.at_end() && (h.declared_points == 0 || count < h.declared_points)) {
    if (c.peek_line().find(':') != std::string_view::npos) break;  // the next plot's header
    bool terminated = false;
    std::string_view text = c.next_line(&terminated);
    if (!terminated) break;
    for (std::string_view word : split_words(text)) {
      if (!have_index) {
        if (parse_number<std::size_t>(word) != count) {
          fail(c.where(), fmt::format("expected point index {}, got {}", count, quote(word)));
        }
        have_index = true;
        continue;
      }
      auto value = parse_number<double>(word);
      if (!value) fail(c.where(), fmt::format("expected a number, got {}", quote(word)));
      point.push_back(*value);
      if (point.size() == width) {
        for (std::size_t j = 0; j < width; ++j) h.plot.columns[j].push_back(point[j]);
        point.clear();
        have_index = false;
        ++count;
      }
    }
  }
  if ((have_index || !point.empty()) && !c.at_end()) {
    fail(c.where(), fmt::format("point {} has {} of {} values", count, point.size(), width));
  }
}

}  // namespace

std::vector<Plot> read_rawfile(std::string_view bytes) {
  Cursor c{bytes};
  std::vector<Plot> plots;
  while (true) {
    while (!c.at_end() && trim(c.peek_line()).empty()) c.next_line();
    if (c.at_end()) break;
    Header h = read_header(c);
    bool more = true;
    if (h.binary) more = read_binary(c, h);
    else read_values(c, h);
    plots.push_back(std::move(h.plot));
    if (!more) break;
  }
  if (plots.empty()) throw Error("rawfile is empty", Error::Kind::simulator);
  return plots;
}

void check_complete(const Plot& plot) {
  if (plot.points() < plot.declared_points)
    throw Error(fmt::format("ngspice's output is cut short: its rawfile holds {} of the {} points the "
                            "header declares (a full disk?)", plot.points(), plot.declared_points),
                Error::Kind::simulator);
}

}  // namespace gearpatch::spice
