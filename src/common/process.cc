#include "common/process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <thread>

#include "common/interrupt.h"

extern char** environ;

namespace gearpatch {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

/// The parent's environment with a C numeric locale: ngspice and gnuplot read
/// and write numbers through the locale, and "1,5" is not 1.5.
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
  return fs::is_regular_file(path, ec) && ::access(path.c_str(), X_OK) == 0;
}

/// posix_spawn's file actions and attributes, destroyed on every way out;
/// every call is checked, since a failed one would start the child wrongly.
class SpawnSetup {
 public:
  explicit SpawnSetup(const ChildSpec& spec) : spec_(spec) {
    check(posix_spawn_file_actions_init(&actions_), "file actions");
    if (int err = posix_spawnattr_init(&attr_); err != 0) {
      posix_spawn_file_actions_destroy(&actions_);
      fail("attributes", err);
    }
    check(posix_spawn_file_actions_addchdir_np(&actions_, spec.directory.c_str()), "working directory");
    check(posix_spawn_file_actions_addopen(&actions_, 0, "/dev/null", O_RDONLY, 0), "stdin");
    constexpr int kFlags = O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW;
    check(posix_spawn_file_actions_addopen(&actions_, 1, spec.stdout_file.c_str(), kFlags, 0600), "stdout");
    check(posix_spawn_file_actions_addopen(&actions_, 2, spec.stderr_file.c_str(), kFlags, 0600), "stderr");
    sigset_t none, all;
    sigemptyset(&none);
    sigfillset(&all);
    check(posix_spawnattr_setflags(&attr_, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF),
          "flags");
    check(posix_spawnattr_setpgroup(&attr_, 0), "process group");
    check(posix_spawnattr_setsigmask(&attr_, &none), "signal mask");
    check(posix_spawnattr_setsigdefault(&attr_, &all), "signal defaults");
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
  ~SpawnSetup() { release(); }
  const posix_spawn_file_actions_t* actions() const { return &actions_; }
  const posix_spawnattr_t* attr() const { return &attr_; }

 private:
  void release() {
    posix_spawn_file_actions_destroy(&actions_);
    posix_spawnattr_destroy(&attr_);
  }
  void check(int err, const char* what) {
    if (err == 0) return;
    release();  // a constructor that throws gets no destructor
    fail(what, err);
  }
  [[noreturn]] void fail(const char* what, int err) const {
    throw Error(fmt::format("cannot start {}: setting up its {}: {}", spec_.name, what, std::strerror(err)),
                spec_.failure_kind);
  }

  const ChildSpec& spec_;
  posix_spawn_file_actions_t actions_;
  posix_spawnattr_t attr_;
};

/// A started child; the destructor kills its group and reaps it, so no child
/// outlives a failed or abandoned run.
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {}
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() { kill(); }
  std::optional<int> poll() {
    auto status = interrupt::poll_child(pid_);
    if (status) pid_ = -1;
    return status;
  }
  void kill() {
    if (pid_ > 0) interrupt::kill_child(pid_);
    pid_ = -1;
  }

 private:
  pid_t pid_;
};

pid_t spawn(const ChildSpec& spec) {
  const auto program = find_executable(spec.program);
  if (!program)
    throw Error(fmt::format("{} was not found (tried '{}'); install it, e.g. '{}'", spec.name, spec.program,
                            spec.install_hint),
                spec.failure_kind);
  std::vector<std::string> args = {program->string()};
  args.insert(args.end(), spec.args.begin(), spec.args.end());
  std::vector<std::string> env = child_environment();
  auto argv = c_strings(args);
  auto envp = c_strings(env);
  SpawnSetup setup(spec);
  return interrupt::add_child([&] {
    pid_t pid = -1;
    if (int err = posix_spawn(&pid, program->c_str(), setup.actions(), setup.attr(), argv.data(), envp.data());
        err != 0)
      throw Error(fmt::format("cannot start {} '{}': {}", spec.name, program->string(), std::strerror(err)),
                  spec.failure_kind);
    return pid;
  }, spec.stops_itself);
}

std::uintmax_t size_or_zero(const fs::path& path) {
  std::error_code ec;
  auto size = fs::file_size(path, ec);
  return ec ? 0 : size;
}

std::string seconds(std::chrono::milliseconds d) { return fmt::format("{:g}", std::chrono::duration<double>(d).count()); }

}  // namespace

std::optional<fs::path> find_executable(const std::string& program) {
  if (program.empty()) return std::nullopt;
  if (program.find('/') != std::string::npos)
    return is_executable_file(program) ? std::optional(fs::absolute(program)) : std::nullopt;
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  for (std::string_view dirs(path);;) {
    const auto colon = std::min(dirs.find(':'), dirs.size());
    const fs::path candidate = fs::path(colon == 0 ? "." : dirs.substr(0, colon)) / program;
    if (is_executable_file(candidate)) return fs::absolute(candidate);
    if (colon == dirs.size()) return std::nullopt;
    dirs.remove_prefix(colon + 1);
  }
}

ChildExit run_child(const ChildSpec& spec) {
  Child child(spawn(spec));
  const auto start = std::chrono::steady_clock::now();
  auto check_size = [&] {
    std::uintmax_t bytes = size_or_zero(spec.stdout_file) + size_or_zero(spec.stderr_file);
    for (const auto& file : spec.counted_files) bytes += size_or_zero(file);
    if (bytes > spec.max_output_bytes) {
      child.kill();
      throw Error(fmt::format("{} output exceeded the cap of {} bytes (wrote {}); killed", spec.name,
                              spec.max_output_bytes, bytes),
                  spec.failure_kind);
    }
  };
  // Polls at growing intervals so that short runs return quickly.
  for (auto delay = 1ms;; delay = std::min<std::chrono::milliseconds>(delay * 2, 50ms)) {
    if (auto status = child.poll()) {
      check_size();  // a fast run can pass the cap between two polls
      if (WIFSIGNALED(*status)) return {128 + WTERMSIG(*status), WTERMSIG(*status)};
      return {WEXITSTATUS(*status), std::nullopt};
    }
    // Compared in milliseconds: the timeout in nanoseconds could overflow.
    const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
    if (elapsed > spec.timeout) {
      child.kill();
      throw Error(fmt::format("{} timed out after {} s; killed", spec.name, seconds(spec.timeout)), spec.failure_kind);
    }
    check_size();
    std::this_thread::sleep_for(delay);
  }
}

std::chrono::milliseconds timeout_from_seconds(double seconds, const std::string& option) {
  constexpr double kLongest = 1e9;  // s, about 30 years: "no limit" in practice
  if (std::isnan(seconds) || seconds <= 0)
    throw Error(fmt::format("{} {}: must be a number of seconds > 0", option, seconds));
  if (seconds < 1e-3) throw Error(fmt::format("{} {}: must be at least 0.001 s (one millisecond)", option, seconds));
  return std::chrono::milliseconds(std::llround(std::min(seconds, kLongest) * 1000));
}

}  // namespace gearpatch
