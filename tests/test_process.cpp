// Tests of the child-process helper (common/process.h, scratch_dir.h,
// interrupt.h): limits, and what SIGINT, SIGTERM and SIGHUP leave behind.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "common/process.h"
#include "common/scratch_dir.h"
#include "support.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using namespace gearpatch;

extern char** environ;

namespace {

/// A fresh folder of the test's own, removed at the end.
struct TestDir : testing::TempFolder {
  TestDir() : TempFolder("process") {}
};

void write_script(const fs::path& file, const std::string& body) {
  std::ofstream(file) << "#!/bin/sh\n" << body << "\n";
  fs::permissions(file, fs::perms::owner_all);
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool process_gone(pid_t pid) {
  if (kill(pid, 0) != 0) return errno == ESRCH;
  std::string stat = slurp(fmt::format("/proc/{}/stat", pid));  // a zombie is gone too
  auto close = stat.rfind(')');
  return close != std::string::npos && stat.size() > close + 2 && stat[close + 2] == 'Z';
}

/// Starts `args` with PATH and TMPDIR replaced; stdout and stderr to `log`.
pid_t start(const std::vector<std::string>& args, const std::string& path, const fs::path& tmpdir,
            const fs::path& log) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (!std::string_view(*e).starts_with("PATH=") && !std::string_view(*e).starts_with("TMPDIR=")) env.push_back(*e);
  env.push_back("PATH=" + path);
  env.push_back("TMPDIR=" + tmpdir.string());
  std::vector<char*> argv, envp;
  for (auto& a : const_cast<std::vector<std::string>&>(args)) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int err = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE(err == 0);
  return pid;
}

bool wait_for_file(const fs::path& file, std::chrono::milliseconds limit) {
  for (auto waited = 0ms; waited < limit; waited += 20ms) {
    if (fs::exists(file) && !slurp(file).empty()) return true;
    std::this_thread::sleep_for(20ms);
  }
  return false;
}

}  // namespace

TEST_CASE("a signal to verify kills ngspice's group, removes its scratch folder and ends by the signal",
          "[common]") {
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    INFO("signal " << sig);
    TestDir test;
    const fs::path bin = test.path / "bin", tmp = test.path / "tmp";
    fs::create_directories(bin);
    fs::create_directories(tmp);
    // The fake ngspice and a grandchild of it sleep; both write their pid.
    write_script(bin / "ngspice", fmt::format("sleep 60 &\necho $! > {0}/sleep.pid\necho $$ > {0}/ngspice.pid\nwait",
                                              test.path.string()));
    const pid_t verify = start({GEARPATCH_BINARY, "verify", testing::source_path("scenes/bild5a.ini")},
                               bin.string() + ":/usr/bin:/bin", tmp, test.path / "log.txt");
    REQUIRE(wait_for_file(test.path / "ngspice.pid", 20s));
    REQUIRE(wait_for_file(test.path / "sleep.pid", 5s));
    const pid_t ngspice = std::stoi(slurp(test.path / "ngspice.pid"));
    const pid_t sleeper = std::stoi(slurp(test.path / "sleep.pid"));
    CHECK(!fs::is_empty(tmp));  // the scratch folder with the deck

    REQUIRE(kill(verify, sig) == 0);
    int status = 0;
    REQUIRE(waitpid(verify, &status, 0) == verify);
    CHECK(WIFSIGNALED(status));
    if (WIFSIGNALED(status)) CHECK(WTERMSIG(status) == sig);
    bool gone = false;
    for (int i = 0; i < 100 && !gone; ++i, std::this_thread::sleep_for(20ms))
      gone = process_gone(ngspice) && process_gone(sleeper);
    CHECK(gone);
    if (!gone) {
      kill(ngspice, SIGKILL);
      kill(sleeper, SIGKILL);
    }
    CHECK(fs::is_empty(tmp));  // no scratch folder left
    INFO(slurp(test.path / "log.txt"));
    CHECK(slurp(test.path / "log.txt").find("killed") == std::string::npos);  // no report of the kill
  }
}

TEST_CASE("a signal to a sweep or Monte Carlo pool stops every worker, its ngspice and every scratch folder",
          "[common]") {
  for (const std::string command : {"sweep", "monte-carlo"}) {
    for (int sig : {SIGTERM, SIGINT}) {
      INFO(command << ", signal " << sig);
      TestDir test;
      const fs::path bin = test.path / "bin", tmp = test.path / "tmp", pids = test.path / "pids";
      fs::create_directories(bin);
      fs::create_directories(tmp);
      fs::create_directories(pids);
      // Each fake ngspice and its grandchild sleep; both write their pid into pids/.
      write_script(bin / "ngspice", fmt::format("sleep 60 &\necho $! > {0}/sleep.$!\necho $$ > {0}/ngspice.$$\nwait",
                                                pids.string()));
      std::vector<std::string> args{GEARPATCH_BINARY, command, testing::source_path("scenes/bild5a.ini"), "--jobs", "2"};
      if (command == "sweep") args.insert(args.end(), {"--set", "gear.restitution=0.5,1", "--verify"});
      else args.insert(args.end(), {"-n", "2"});
      const pid_t pool = start(args, bin.string() + ":/usr/bin:/bin", tmp, test.path / "log.txt");
      std::vector<pid_t> started;
      for (int i = 0; i < 1000 && started.size() < 4; ++i) {
        std::this_thread::sleep_for(20ms);
        started.clear();
        for (const auto& entry : fs::directory_iterator(pids))
          if (!slurp(entry.path()).empty()) started.push_back(std::stoi(slurp(entry.path())));
      }
      REQUIRE(started.size() == 4);  // two workers, each with an ngspice and its sleep

      REQUIRE(kill(pool, sig) == 0);
      int status = 0;
      REQUIRE(waitpid(pool, &status, 0) == pool);
      CHECK(WIFSIGNALED(status));
      if (WIFSIGNALED(status)) CHECK(WTERMSIG(status) == sig);
      bool gone = false;
      for (int i = 0; i < 100 && !gone; ++i, std::this_thread::sleep_for(20ms))
        gone = std::all_of(started.begin(), started.end(), process_gone);
      CHECK(gone);
      if (!gone)
        for (pid_t pid : started) kill(pid, SIGKILL);
      CHECK(fs::is_empty(tmp));  // no worker's scratch folder, no run folder left
    }
  }
}

namespace {

/// A child "tool" in the test's folder running `body`, its output in files there.
ChildSpec tool_spec(const TestDir& test, const std::string& body) {
  write_script(test.path / "tool", body);
  ChildSpec spec;
  spec.name = "tool";
  spec.program = (test.path / "tool").string();
  spec.directory = test.path;
  spec.stdout_file = test.path / "out.txt";
  spec.stderr_file = test.path / "err.txt";
  return spec;
}

}  // namespace

TEST_CASE("run_child passes arguments without a shell and reports exit codes and signals", "[common]") {
  TestDir test;
  ChildSpec spec = tool_spec(test, "echo \"$1|$2|$LC_NUMERIC\"; pwd >&2; exit 7");
  spec.args = {"a b; echo injected", "$HOME"};
  const ChildExit exit = run_child(spec);
  CHECK(exit.exit_code == 7);
  CHECK_FALSE(exit.signal);
  CHECK(slurp(spec.stdout_file) == "a b; echo injected|$HOME|C\n");
  CHECK(fs::equivalent(fs::path(slurp(spec.stderr_file).substr(0, slurp(spec.stderr_file).size() - 1)), test.path));

  write_script(test.path / "tool", "kill -TERM $$");
  const ChildExit killed = run_child(spec);
  REQUIRE(killed.signal);
  CHECK(*killed.signal == SIGTERM);

  spec.program = "gearpatch-no-such-tool";
  spec.install_hint = "apt-get install tool";
  CHECK_THROWS_WITH(run_child(spec), "tool was not found (tried 'gearpatch-no-such-tool'); install it, e.g. "
                                     "'apt-get install tool'");
}

TEST_CASE("a huge timeout is no instant timeout; nonsense timeouts are refused", "[common]") {
  TestDir test;
  ChildSpec spec = tool_spec(test, "exit 0");
  for (double seconds : {1e12, 1e300, std::numeric_limits<double>::infinity()}) {
    spec.timeout = timeout_from_seconds(seconds);
    CHECK(run_child(spec).exit_code == 0);
  }
  // The largest duration representable: compared without overflow all the same.
  spec.timeout = std::chrono::milliseconds::max();
  CHECK(run_child(spec).exit_code == 0);
  CHECK(timeout_from_seconds(0.0015) == 2ms);
  CHECK(timeout_from_seconds(300) == 300'000ms);
  CHECK_THROWS_WITH(timeout_from_seconds(0.0004), "--timeout 0.0004: must be at least 0.001 s (one millisecond)");
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()})
    CHECK_THROWS_WITH(timeout_from_seconds(bad), Catch::StartsWith("--timeout") && Catch::EndsWith("must be a number of seconds > 0"));
}

TEST_CASE("verify and bench take huge timeouts and refuse sub-millisecond ones", "[common]") {
  const std::string verify = std::string(GEARPATCH_BINARY) + " verify " + testing::source_path("scenes/bild5a.ini");
  std::string output;
  CHECK(testing::run_command(verify + " --timeout 1e12", output) == 0);
  CHECK_THAT(output, Catch::Contains("PASS"));
  CHECK(testing::run_command(verify + " --timeout 1e300", output) == 0);
  CHECK_THAT(output, Catch::Contains("PASS"));
  CHECK(testing::run_command(verify + " --timeout 0.0004", output) == 2);
  CHECK_THAT(output, Catch::Contains("--timeout 0.0004: must be at least 0.001 s"));
  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " bench " + testing::source_path("scenes/bild5a.ini") +
                                 " --only level --timeout 0.0004",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("--timeout 0.0004: must be at least 0.001 s"));
}

TEST_CASE("a scratch folder is private, fresh and removed unless kept", "[common]") {
  fs::path kept;
  {
    ScratchDir a("gearpatch-test"), b("gearpatch-test");
    CHECK(a.path() != b.path());
    CHECK((fs::status(a.path()).permissions() & fs::perms::all) == fs::perms::owner_all);
    std::ofstream(a / "file") << "x";
    b.keep();
    kept = b.path();
  }
  CHECK(fs::exists(kept));
  fs::remove_all(kept);
}
