#include "spice/batch_ngspice.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "spice/rawfile.h"

extern char** environ;

namespace gearpatch::spice {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

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

std::optional<std::string> diagnose_ngspice_failure(std::string_view stdout_text,
                                                    std::string_view stderr_text,
                                                    int exit_status) {
  std::string all = std::string(stderr_text) + "\n" + std::string(stdout_text);
  if (auto message = timestep_too_small(all)) return message;
  // With a .control block the exit status is whatever `quit` says, so an abort
  // counts even when the status is 0.
  if (all.find("simulation(s) aborted") != std::string::npos) {
    return "ngspice aborted the simulation: " + last_words(stdout_text, stderr_text);
  }
  if (exit_status == 0) return std::nullopt;
  auto errors = error_lines(stderr_text);
  if (errors.empty()) errors = error_lines(stdout_text);
  if (!errors.empty()) return "ngspice could not run the deck: " + join_quoted(errors);
  return fmt::format("ngspice failed with exit status {}: {}", exit_status,
                     last_words(stdout_text, stderr_text));
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
std::string read_file(const fs::path& path, std::uintmax_t limit = std::uintmax_t{1} << 20) {
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

std::uintmax_t size_or_zero(const fs::path& path) {
  std::error_code ec;
  auto size = fs::file_size(path, ec);
  return ec ? 0 : size;
}

/// A private directory for one run (mkdtemp: no other user can plant files in
/// it). Removed at the end unless a failure asks to keep it for inspection.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "gearpatch-ngspice-XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
      throw Error(fmt::format("cannot create a temporary directory {}: {}", pattern, std::strerror(errno)), kSimulator);
    }
    path_ = pattern;
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ec;
    if (!keep_) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  void keep() { keep_ = true; }

 private:
  fs::path path_;
  bool keep_ = false;
};

// ---------------------------------------------------------------- process

/// A running ngspice in its own process group. The destructor kills the group
/// and reaps it, so no ngspice outlives a failed or abandoned run.
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {}
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() { kill_and_reap(); }

  /// The wait status once the process has ended, nothing while it runs.
  std::optional<int> poll() {
    int status = 0;
    pid_t r = waitpid(pid_, &status, WNOHANG);
    if (r == 0 || (r < 0 && errno == EINTR)) return std::nullopt;
    pid_ = -1;
    if (r < 0) throw Error(fmt::format("waiting for ngspice failed: {}", std::strerror(errno)), kSimulator);
    return status;
  }

  void kill_and_reap() {
    if (pid_ <= 0) return;
    ::kill(-pid_, SIGKILL);
    while (waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
  }

 private:
  pid_t pid_;
};

/// The parent's environment with a C numeric locale: ngspice reads and writes
/// numbers through the locale, and "1,5" is not 1.5.
std::vector<std::string> child_environment() {
  std::vector<std::string> env;
  for (char** e = environ; e && *e; ++e) {
    std::string_view entry(*e);
    if (entry.starts_with("LC_ALL=") || entry.starts_with("LC_NUMERIC=")) continue;
    env.emplace_back(entry);
  }
  env.emplace_back("LC_ALL=C");
  env.emplace_back("LC_NUMERIC=C");
  return env;
}

std::vector<char*> c_strings(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

bool is_executable_file(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && access(path.c_str(), X_OK) == 0;
}

/// The absolute path of the executable, looked up in PATH as a shell would.
/// Done here rather than left to exec, because not every way of spawning
/// reports a failed exec (under valgrind the child just exits 127).
fs::path find_executable(const std::string& executable) {
  std::optional<fs::path> found;
  if (executable.find('/') != std::string::npos) {
    if (is_executable_file(executable)) found = fs::absolute(executable);
  } else if (const char* path = std::getenv("PATH")) {
    std::string_view dirs(path);
    while (!found) {
      auto colon = std::min(dirs.find(':'), dirs.size());
      fs::path candidate = fs::path(colon == 0 ? "." : dirs.substr(0, colon)) / executable;
      if (is_executable_file(candidate)) found = fs::absolute(candidate);
      if (colon == dirs.size()) break;
      dirs.remove_prefix(colon + 1);
    }
  }
  if (!found) {
    throw Error(fmt::format("ngspice was not found (tried '{}'); install it, e.g. 'apt-get install ngspice'", executable),
                kSimulator);
  }
  return *found;
}

/// Starts `ngspice -b -r out.raw deck.cir` in `dir`, no shell, stdout and stderr
/// to files there, in a new process group so that a kill reaches everything.
pid_t spawn_ngspice(const std::string& executable, const fs::path& dir) {
  std::string program = find_executable(executable).string();
  std::vector<std::string> args = {program, "-b", "-r", "out.raw", "deck.cir"};
  std::vector<std::string> env = child_environment();
  auto argv = c_strings(args);
  auto envp = c_strings(env);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, (dir / "stdout.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, 2, (dir / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t no_signals, all_signals;
  sigemptyset(&no_signals);
  sigfillset(&all_signals);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setsigmask(&attr, &no_signals);
  posix_spawnattr_setsigdefault(&attr, &all_signals);

  pid_t pid = -1;
  int err = posix_spawn(&pid, program.c_str(), &actions, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (err != 0) throw Error(fmt::format("cannot start ngspice '{}': {}", program, std::strerror(err)), kSimulator);
  return pid;
}

std::string seconds(std::chrono::milliseconds d) {
  return fmt::format("{:g}", std::chrono::duration<double>(d).count());
}

/// Waits for ngspice while enforcing the limits; returns its wait status.
/// Polls at growing intervals so that short runs return quickly.
int wait_within_limits(Child& child, const fs::path& dir, const RunLimits& limits) {
  const auto start = std::chrono::steady_clock::now();
  auto output_bytes = [&] {
    return size_or_zero(dir / "out.raw") + size_or_zero(dir / "stdout.txt") + size_or_zero(dir / "stderr.txt");
  };
  auto check_size = [&] {
    if (auto bytes = output_bytes(); bytes > limits.max_output_bytes) {
      child.kill_and_reap();
      throw Error(fmt::format("ngspice output exceeded the cap of {} bytes (wrote {}); killed",
                              limits.max_output_bytes, bytes), kSimulator);
    }
  };
  auto delay = 1ms;
  while (true) {
    if (auto status = child.poll()) {
      check_size();  // a fast run can pass the cap between two polls
      return *status;
    }
    if (std::chrono::steady_clock::now() - start > limits.timeout) {
      child.kill_and_reap();
      throw Error(fmt::format("ngspice timed out after {} s; killed", seconds(limits.timeout)), kSimulator);
    }
    check_size();
    std::this_thread::sleep_for(delay);
    delay = std::min<std::chrono::milliseconds>(delay * 2, 50ms);
  }
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
Vectors run_in(const std::string& executable, const fs::path& dir, const RunLimits& limits) {
  Child child(spawn_ngspice(executable, dir));
  int status = wait_within_limits(child, dir, limits);
  std::string out = read_file(dir / "stdout.txt");
  std::string err = read_file(dir / "stderr.txt");
  if (WIFSIGNALED(status)) {
    throw Error(fmt::format("ngspice was killed by signal {}: {}", WTERMSIG(status), last_words(out, err)), kSimulator);
  }
  if (auto message = diagnose_ngspice_failure(out, err, WEXITSTATUS(status))) throw Error(*message, kSimulator);
  if (!fs::exists(dir / "out.raw")) {
    throw Error("ngspice wrote no rawfile: " + last_words(out, err), kSimulator);
  }
  auto plots = read_rawfile(read_file(dir / "out.raw", std::numeric_limits<std::uintmax_t>::max()));
  check_complete(plots.back());
  return to_vectors(plots.back());
}

/// Batch ngspice as a Simulator: one child process and one private directory per run.
class BatchNgspice : public Simulator {
 public:
  explicit BatchNgspice(std::string executable) : executable_(std::move(executable)) {}

  Vectors run(const std::string& deck, const RunLimits& limits) override {
    if (!limits.keep_deck_as.empty()) write_file(limits.keep_deck_as, deck);
    TempDir dir;
    write_file(dir.path() / "deck.cir", deck);
    try {
      return run_in(executable_, dir.path(), limits);
    } catch (const Error& e) {
      // Keep the deck for a rerun by hand; the rawfile can be huge and is dropped.
      std::string kept = limits.keep_deck_as;
      if (kept.empty()) {
        dir.keep();
        std::error_code ec;
        fs::remove(dir.path() / "out.raw", ec);
        kept = (dir.path() / "deck.cir").string();
      }
      throw Error(fmt::format("{} (deck kept at {})", e.what(), kept), kSimulator);
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
