#include "spice/batch_ngspice.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/process.h"
#include "common/scratch_dir.h"
#include "spice/rawfile.h"

namespace gearpatch::spice {

namespace fs = std::filesystem;

namespace {

constexpr auto kSimulator = Error::Kind::simulator;

// ---------------------------------------------------------------- console text

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> lines;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) {
    auto first = line.find_first_not_of(" \t\r");
    auto last = line.find_last_not_of(" \t\r");
    lines.push_back(first == std::string::npos ? "" : line.substr(first, last - first + 1));
  }
  return lines;
}

bool contains_nocase(std::string_view text, std::string_view word) {
  auto it = std::search(text.begin(), text.end(), word.begin(), word.end(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
  });
  return it != text.end();
}

/// ngspice's chatter that never explains a failure: resource statistics,
/// notes, and the generic "interrupted due to error" that follows the real one.
bool is_noise(std::string_view line) {
  static constexpr std::string_view kNoise[] = {
      "Note:", "or no active circuit", "Simulation interrupted due to error",
      "run simulation(s) aborted", "Total elapsed time", "Total DRAM", "DRAM currently",
      "Maximum ngspice program size", "Current ngspice program size", "Shared ngspice pages",
      "Text (code) pages", "Stack =", "Library pages", "Circuit:", "Doing analysis at",
      "Using SPARSE", "Trying gmin", "Supplies reduced", "******", "** ngspice", "** The U. C.",
      "** Please", "** Creation Date", "binary raw file", "ASCII raw file"};
  if (line.empty()) return true;
  return std::any_of(std::begin(kNoise), std::end(kNoise),
                     [&](std::string_view n) { return line.find(n) != std::string_view::npos; });
}

std::string join_quoted(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& line : lines) out += (out.empty() ? "" : " / ") + line;
  if (out.size() > 400) out = out.substr(0, 400) + "...";
  return out;
}

/// From the first line that says "error" on, the lines that explain it.
std::vector<std::string> error_lines(std::string_view text) {
  std::vector<std::string> picked;
  for (const auto& line : lines_of(text)) {
    if (is_noise(line)) continue;
    if (picked.empty() && !contains_nocase(line, "error")) continue;
    picked.push_back(line);
    if (picked.size() == 6) break;
  }
  return picked;
}

std::vector<std::string> last_lines(std::string_view text, std::size_t n) {
  std::vector<std::string> kept;
  for (const auto& line : lines_of(text)) {
    if (!is_noise(line)) kept.push_back(line);
  }
  if (kept.size() > n) kept.erase(kept.begin(), kept.end() - static_cast<std::ptrdiff_t>(n));
  return kept;
}

/// The last lines worth quoting: stderr first, where ngspice writes its errors.
std::string last_words(std::string_view out, std::string_view err) {
  auto lines = last_lines(err, 3);
  if (lines.empty()) lines = last_lines(out, 3);
  return lines.empty() ? "no message" : join_quoted(lines);
}

std::optional<std::string> timestep_too_small(const std::string& text) {
  static const std::regex pattern(
      R"(Timestep too small; time = ([^,\n]+), timestep = ([^:\n]+):[ \t]*([^\n]*))");
  std::smatch m;
  if (!std::regex_search(text, m, pattern)) return std::nullopt;
  std::string cause = m[3].str();
  while (!cause.empty() && std::isspace(static_cast<unsigned char>(cause.back()))) cause.pop_back();
  return fmt::format("ngspice aborted: timestep too small at time = {} s (timestep {} s): {}",
                     m[1].str(), m[2].str(), cause.empty() ? "no cause given" : cause);
}

}  // namespace

std::optional<NgspiceFailure> diagnose_ngspice_failure(std::string_view stdout_text,
                                                    std::string_view stderr_text,
                                                    int exit_status) {
  std::string all = std::string(stderr_text) + "\n" + std::string(stdout_text);
  if (auto message = timestep_too_small(all)) return NgspiceFailure{*message, true};
  // With a .control block the exit status is whatever `quit` says, so an abort
  // counts even when the status is 0.
  if (all.find("simulation(s) aborted") != std::string::npos) {
    return NgspiceFailure{"ngspice aborted the simulation: " + last_words(stdout_text, stderr_text), true};
  }
  if (exit_status == 0) return std::nullopt;
  auto errors = error_lines(stderr_text);
  if (errors.empty()) errors = error_lines(stdout_text);
  if (!errors.empty()) return NgspiceFailure{"ngspice could not run the deck: " + join_quoted(errors)};
  return NgspiceFailure{
      fmt::format("ngspice failed with exit status {}: {}", exit_status, last_words(stdout_text, stderr_text))};
}

namespace {

// ---------------------------------------------------------------- files

void write_file(const fs::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw Error(fmt::format("cannot write the deck to {}: {}", path.string(), std::strerror(errno)), kSimulator);
}

/// The whole file, or its last `limit` bytes: a chattering run's log can be
/// huge, and what explains its end is at its end.
std::string read_tail(const fs::path& path, std::uintmax_t limit = std::uintmax_t{1} << 20) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  in.seekg(0, std::ios::end);
  auto size = static_cast<std::uintmax_t>(in.tellg());
  auto start = size > limit ? size - limit : 0;
  in.seekg(static_cast<std::streamoff>(start));
  std::string bytes(size - start, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// ---------------------------------------------------------------- result

Vectors to_vectors(const Plot& plot) {
  Vectors v;
  for (std::size_t i = 0; i < plot.variables.size(); ++i) v.data[plot.variables[i].name] = plot.columns[i];
  if (!v.has("time")) {
    throw Error(fmt::format("ngspice's last plot '{}' has no 'time' vector (not a transient analysis)", plot.name),
                kSimulator);
  }
  return v;
}

/// Runs the deck already written to dir/deck.cir and reads the result.
Vectors run_in(const std::string& executable, const ScratchDir& dir, const RunLimits& limits) {
  ChildSpec spec;
  spec.name = "ngspice";
  spec.program = executable;
  spec.install_hint = "apt-get install ngspice";
  spec.args = {"-b", "-r", "out.raw", "deck.cir"};
  spec.directory = dir.path();
  spec.stdout_file = dir / "stdout.txt";
  spec.stderr_file = dir / "stderr.txt";
  spec.counted_files = {dir / "out.raw"};
  spec.timeout = limits.timeout;
  spec.max_output_bytes = limits.max_output_bytes;
  const ChildExit exit = run_child(spec);
  std::string out = read_tail(spec.stdout_file);
  std::string err = read_tail(spec.stderr_file);
  if (exit.signal) {
    throw Error(fmt::format("ngspice was killed by signal {}: {}", *exit.signal, last_words(out, err)), kSimulator);
  }
  if (auto failure = diagnose_ngspice_failure(out, err, exit.exit_code))
    throw failure->numerical_abort ? Error::numerical_abort(failure->message) : Error(failure->message, kSimulator);
  if (!fs::exists(dir / "out.raw")) {
    throw Error("ngspice wrote no rawfile: " + last_words(out, err), kSimulator);
  }
  auto plots = read_rawfile(read_tail(dir / "out.raw", std::numeric_limits<std::uintmax_t>::max()));
  check_complete(plots.back());
  return to_vectors(plots.back());
}

/// Batch ngspice as a Simulator: one child process and one private directory per run.
class BatchNgspice : public Simulator {
 public:
  explicit BatchNgspice(std::string executable) : executable_(std::move(executable)) {}

  Vectors run(const std::string& deck, const RunLimits& limits) override {
    // Kept whatever the outcome: it is there to rerun a failure by hand.
    if (!limits.keep_deck_as.empty()) write_file_atomically(limits.keep_deck_as, deck);
    ScratchDir dir("gearpatch-ngspice", kSimulator);
    write_file(dir / "deck.cir", deck);
    try {
      return run_in(executable_, dir, limits);
    } catch (const Error& e) {
      // Keep the deck for a rerun by hand; the rawfile can be huge and is dropped.
      std::string kept = limits.keep_deck_as;
      if (kept.empty()) {
        dir.keep();
        std::error_code ec;
        fs::remove(dir.path() / "out.raw", ec);
        kept = (dir.path() / "deck.cir").string();
      }
      const std::string message = fmt::format("{} (deck kept at {})", e.what(), kept);
      throw e.is_numerical_abort() ? Error::numerical_abort(message) : Error(message, kSimulator);
    }
  }

 private:
  std::string executable_;
};

}  // namespace

const std::vector<double>& Vectors::at(const std::string& name) const {
  auto it = data.find(name);
  if (it != data.end()) return it->second;
  std::string names;
  for (const auto& [key, values] : data) names += (names.empty() ? "" : ", ") + key;
  throw Error(fmt::format("no vector '{}' in the simulation result (available: {})", name,
                          names.empty() ? "none" : names),
              kSimulator);
}

std::unique_ptr<Simulator> make_batch_ngspice(std::string executable) {
  return std::make_unique<BatchNgspice>(std::move(executable));
}

}  // namespace gearpatch::spice
