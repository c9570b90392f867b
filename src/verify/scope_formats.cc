// Readers of the CSV exports of oscilloscopes, each as its maker's manual shows
// the layout. Values stay in volts and scope seconds: converting them to the
// gear's units is measured_trace.cc's job.
#include "verify/scope_formats.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "common/error.h"

namespace gearpatch::verify {
namespace {

/// The text as lines of fields: CRLF or LF, comma-separated (a plain CSV may
/// use ';' or a tab), quotes and surrounding blanks removed. Keeps the line number.
struct Row {
  std::size_t line = 0;
  std::vector<std::string> fields;
};

std::string trim(std::string s) {
  const auto blank = [](unsigned char c) { return std::isspace(c) || c == '"'; };
  while (!s.empty() && blank(s.back())) s.pop_back();
  std::size_t from = 0;
  while (from < s.size() && blank(s[from])) ++from;
  return s.substr(from);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<Row> split_rows(const std::string& text) {
  std::vector<Row> rows;
  std::size_t line = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string s = text.substr(at, end - at);
    at = end + 1, ++line;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    if (trim(s).empty()) continue;
    const char separator = s.find(',') != std::string::npos ? ',' : s.find(';') != std::string::npos ? ';' : '\t';
    Row row{line, {}};
    for (std::size_t from = 0;;) {
      const std::size_t cut = s.find(separator, from);
      row.fields.push_back(trim(s.substr(from, cut == std::string::npos ? std::string::npos : cut - from)));
      if (cut == std::string::npos) break;
      from = cut + 1;
    }
    // Rigol ends each row with a comma: the empty last field is no column.
    if (row.fields.size() > 1 && row.fields.back().empty()) row.fields.pop_back();
    rows.push_back(std::move(row));
  }
  return rows;
}

std::optional<double> number(const std::string& field) {
  std::string s = field;
  if (!s.empty() && s.front() == '+') s.erase(0, 1);  // InfiniiVision writes "+0.0E+00"
  double x = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

bool numeric(const Row& row) {
  return std::all_of(row.fields.begin(), row.fields.end(), [](const std::string& f) { return number(f).has_value(); });
}

[[noreturn]] void refuse(const std::string& path, std::size_t line, const std::string& what) {
  throw Error(fmt::format("{}:{}: {}", path, line, what));
}

double field_number(const Row& row, std::size_t k, const std::string& path) {
  if (k >= row.fields.size())
    refuse(path, row.line, fmt::format("{} fields, the header names {} columns", row.fields.size(), k + 1));
  const auto x = number(row.fields[k]);
  if (!x) refuse(path, row.line, fmt::format("'{}' (column {}) is not a number", row.fields[k], k + 1));
  return *x;
}

/// Data rows from `first` on: column 0 the time (or the sample index), the
/// rest the channels; `scales` multiplies each column (units).
void read_data(const std::vector<Row>& rows, std::size_t first, const std::vector<double>& scales,
               const std::string& path, std::vector<double>& t, std::vector<ScopeColumn>& columns) {
  for (std::size_t r = first; r < rows.size(); ++r) {
    const Row& row = rows[r];
    if (!row.fields.empty() && row.fields.front().rfind('#', 0) == 0) continue;
    t.push_back(field_number(row, 0, path) * scales[0]);
    for (std::size_t k = 0; k < columns.size(); ++k)
      columns[k].volts.push_back(field_number(row, k + 1, path) * scales[k + 1]);
  }
  if (t.size() < 2) refuse(path, rows.empty() ? 1 : rows.back().line, "fewer than two samples");
}

std::vector<ScopeColumn> columns_named(const Row& header, std::size_t from, std::size_t to) {
  std::vector<ScopeColumn> out;
  for (std::size_t k = from; k < to; ++k) out.push_back({header.fields[k], canonical_channel(header.fields[k]), {}});
  return out;
}

/// Keysight/Agilent InfiniiVision 2000/3000/4000 X-Series, "Save to file, CSV
/// data": a first row "x-axis,1,2,..." naming the channels by number, a second
/// row of units "second,Volt,Volt,...", then one row per point: time relative
/// to the trigger, the channels' volts.
ScopeRecording read_keysight(const std::vector<Row>& rows, const std::string& path) {
  if (rows.size() < 3 || lower(rows[0].fields[0]) != "x-axis")
    refuse(path, rows.empty() ? 1 : rows[0].line, "not an InfiniiVision CSV: its first row is x-axis,1,2,...");
  ScopeRecording rec{"keysight", "time column", {}, columns_named(rows[0], 1, rows[0].fields.size()), {}, {}};
  std::vector<double> scales(rows[0].fields.size(), 1.0);
  read_data(rows, 2, scales, path, rec.t, rec.columns);
  return rec;
}

/// Rigol DS1000Z/MSO1000Z "Save, CSV": a first row "X,CH1,CH2,Start,Increment",
/// a second row "Sequence,Volt,Volt,<start>,<increment>", then one row per
/// point: the sample's index and the channels' volts, each row ending in a
/// comma. Time is start + index * increment, start relative to the trigger.
ScopeRecording read_rigol(const std::vector<Row>& rows, const std::string& path) {
  const auto at = [&](const std::string& word) {
    const auto& f = rows[0].fields;
    const auto it = std::find_if(f.begin(), f.end(), [&](const std::string& x) { return lower(x) == word; });
    if (it == f.end()) refuse(path, rows[0].line, "not a Rigol CSV: its first row names no " + word);
    return static_cast<std::size_t>(it - f.begin());
  };
  if (rows.size() < 3) refuse(path, rows.empty() ? 1 : rows[0].line, "not a Rigol CSV: fewer than three rows");
  const std::size_t start_at = at("start"), increment_at = at("increment");
  const double start = field_number(rows[1], start_at, path), increment = field_number(rows[1], increment_at, path);
  if (increment <= 0) refuse(path, rows[1].line, fmt::format("increment {:g} s: must be positive", increment));
  ScopeRecording rec{"rigol", "start + n * increment", {}, columns_named(rows[0], 1, std::min(start_at, increment_at)),
                     {}, {}};
  std::vector<double> scales(rec.columns.size() + 1, 1.0);
  read_data(rows, 2, scales, path, rec.t, rec.columns);
  for (double& t : rec.t) t = start + t * increment;
  return rec;
}

/// The unit of a header field written "CH1 in V" (R&S RTC1000/RTB2000/RTM3000)
/// or "CH1[V]" (R&S RTM2000), or "".
std::string bracketed_unit(const std::string& name) {
  const std::string l = lower(name);
  if (const auto in = l.rfind(" in "); in != std::string::npos) return trim(l.substr(in + 4));
  if (const auto open = l.rfind('['); open != std::string::npos && l.back() == ']')
    return l.substr(open + 1, l.size() - open - 2);
  if (l.rfind("in ", 0) == 0) return trim(l.substr(3));
  return "";
}

double unit_factor(const std::string& unit, bool time, const std::string& path, std::size_t line) {
  const std::string u = lower(unit);
  if (time) {
    if (u == "s" || u == "sec" || u == "second" || u == "seconds" || u.empty()) return 1;
    if (u == "ms") return 1e-3;
    if (u == "us" || u == "µs") return 1e-6;
    if (u == "ns") return 1e-9;
  } else {
    if (u == "v" || u == "volt" || u == "volts" || u.empty()) return 1;
    if (u == "mv") return 1e-3;
  }
  refuse(path, line, fmt::format("unit '{}': a {} column takes {}", unit, time ? "time" : "channel",
                                 time ? "s, ms, us or ns" : "V or mV"));
}

/// Rohde & Schwarz RTC1000, RTB2000, RTM3000 ("in s,CH1 in V,...") and RTM2000
/// ("[s],CH1[V],..."), user manuals, "Waveform file formats, CSV": the first row
/// names each column with its unit, the first column is time relative to the
/// trigger point; with peak detect a time comes twice (minimum, then maximum).
ScopeRecording read_rohde_schwarz(const std::vector<Row>& rows, const std::string& path) {
  if (rows.size() < 2 || numeric(rows[0]))
    refuse(path, rows.empty() ? 1 : rows[0].line, "not an R&S CSV: its first row is 'in s,CH1 in V,...'");
  ScopeRecording rec{"rohde-schwarz", "time column", {}, columns_named(rows[0], 1, rows[0].fields.size()), {}, {}};
  std::vector<double> scales;
  for (std::size_t k = 0; k < rows[0].fields.size(); ++k)
    scales.push_back(unit_factor(bracketed_unit(rows[0].fields[k]), k == 0, path, rows[0].line));
  read_data(rows, 1, scales, path, rec.t, rec.columns);
  return rec;
}

/// A comment "# probe CH1=10 CH2=10" or "# offset CH1=0.05": the channels'
/// probe ratios or offsets (volts), blanks or commas between them. Other
/// comments (no CHANNEL=NUMBER after the word) are notes.
void read_channel_settings(const Row& comment, const std::string& path, ScopeRecording& rec) {
  std::string text;
  for (const std::string& f : comment.fields) text += f + " ";
  std::replace(text.begin(), text.end(), '\t', ' ');
  std::vector<std::string> words;
  for (std::size_t at = 1; at < text.size();) {  // after the '#'
    const std::size_t end = std::min(text.find(' ', at), text.size());
    if (end > at) words.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  const auto setting = [](const std::string& w) { return w.find('=') != std::string::npos; };
  if (words.size() < 2 || (lower(words[0]) != "probe" && lower(words[0]) != "offset") ||
      !std::all_of(words.begin() + 1, words.end(), setting))
    return;
  const bool probe = lower(words[0]) == "probe";
  for (std::size_t k = 1; k < words.size(); ++k) {
    const auto eq = words[k].find('=');
    const auto x = number(words[k].substr(eq + 1));
    if (!x || (probe && *x <= 0))
      refuse(path, comment.line, fmt::format("'# {} {}': write CHANNEL={}", words[0], words[k],
                                             probe ? "RATIO, e.g. CH1=10 (positive)" : "VOLTS, e.g. CH1=0.05"));
    (probe ? rec.probe : rec.offset)[canonical_channel(words[k].substr(0, eq))] = *x;
  }
}

/// A plain CSV: '#' comment lines (among them probe ratios and offsets), a
/// header row (time first, then the channels), an optional row of units (s,
/// ms, us, ns; V, mV), then numbers. Without a header the channels are CH1, CH2, ... in order.
ScopeRecording read_plain(const std::vector<Row>& all, const std::string& path) {
  ScopeRecording rec{"csv", "time column", {}, {}, {}, {}};
  std::vector<Row> rows;
  for (const Row& r : all)
    if (r.fields.front().rfind('#', 0) != 0)
      rows.push_back(r);
    else
      read_channel_settings(r, path, rec);
  if (rows.empty()) refuse(path, 1, "no data");
  std::size_t first = 0;
  std::vector<double> scales(rows[0].fields.size(), 1.0);
  if (!numeric(rows[0])) {
    rec.columns = columns_named(rows[0], 1, rows[0].fields.size());
    first = 1;
    for (std::size_t k = 0; k < rows[0].fields.size(); ++k)  // "t [ms]", "CH1 in mV"
      scales[k] = unit_factor(bracketed_unit(rows[0].fields[k]), k == 0, path, rows[0].line);
    if (rows.size() > 1 && !numeric(rows[1])) {
      for (std::size_t k = 0; k < std::min(scales.size(), rows[1].fields.size()); ++k)
        scales[k] = unit_factor(rows[1].fields[k], k == 0, path, rows[1].line);
      first = 2;
    }
  } else {
    for (std::size_t k = 1; k < rows[0].fields.size(); ++k) rec.columns.push_back({"", fmt::format("CH{}", k), {}});
  }
  if (rec.columns.empty()) refuse(path, rows[0].line, "a time column and no channel");
  read_data(rows, first, scales, path, rec.t, rec.columns);
  return rec;
}

}  // namespace

const ScopeColumn* ScopeRecording::find(const std::string& channel) const {
  const std::string wanted = lower(canonical_channel(channel));
  for (const ScopeColumn& c : columns)
    if (lower(c.channel) == wanted) return &c;
  return nullptr;
}

std::vector<std::string> scope_format_names() { return {"auto", "csv", "keysight", "rigol", "rohde-schwarz"}; }

std::string canonical_channel(const std::string& written) {
  std::string name = trim(written);
  for (const std::string& cut : {std::string(" in "), std::string("["), std::string("(")})
    if (const auto at = lower(name).find(cut); at != std::string::npos && at > 0) name = trim(name.substr(0, at));
  std::string digits = lower(name);
  for (const char* prefix : {"ch", "c"})
    if (digits.rfind(prefix, 0) == 0) {
      digits.erase(0, std::string(prefix).size());
      break;
    }
  const bool number = !digits.empty() && std::all_of(digits.begin(), digits.end(), ::isdigit);
  return number ? "CH" + digits : name;
}

std::string detect_scope_format(const std::string& text) {
  const std::vector<Row> rows = split_rows(text.substr(0, 4096));
  if (rows.empty()) return "csv";
  const auto& f = rows[0].fields;
  const std::string first = lower(f[0]);
  if (first == "x-axis") return "keysight";
  const auto has = [&](const char* w) {
    return std::any_of(f.begin(), f.end(), [&](const std::string& x) { return lower(x) == w; });
  };
  if (first == "x" && has("start") && has("increment")) return "rigol";
  if (first == "in s" || first == "[s]") return "rohde-schwarz";
  return "csv";
}

ScopeRecording read_scope_csv(const std::string& text, const std::string& path, const std::string& format) {
  const std::string chosen = format == "auto" ? detect_scope_format(text) : format;
  const std::vector<Row> rows = split_rows(text);
  if (rows.empty()) refuse(path, 1, "empty: no recording");
  if (chosen == "keysight") return read_keysight(rows, path);
  if (chosen == "rigol") return read_rigol(rows, path);
  if (chosen == "rohde-schwarz") return read_rohde_schwarz(rows, path);
  if (chosen == "csv") return read_plain(rows, path);
  throw Error(fmt::format("--format {}: one of auto, csv, keysight, rigol, rohde-schwarz", format));
}

}  // namespace gearpatch::verify
