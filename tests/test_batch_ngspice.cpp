// Tests of the batch ngspice runner against the real ngspice (and a few fake
// executables for what ngspice cannot be made to do on demand), plus the
// scripted simulator and Vectors.
#include <catch2/catch.hpp>

#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "common/error.h"
#include "spice/batch_ngspice.h"
#include "spice/retry.h"
#include "spice/scripted_simulator.h"
#include "support.h"

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using gearpatch::Error;
using namespace gearpatch::spice;

namespace {

constexpr const char* kRcDeck = gearpatch::testing::rc_step_deck;

// A sine into an RC with a 1 ns maximum step over 10 s: about 10 MB of
// rawfile per second, for ever as far as a test is concerned.
constexpr const char* kEndlessDeck =
    "endless transient\n"
    "V1 in 0 SIN(0 1 1k)\n"
    "R1 in out 1k\n"
    "C1 out 0 1u\n"
    ".tran 1n 10 0 1n\n"
    ".end\n";

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs and expects an Error of kind simulator; returns its message.
std::string failure_of(Simulator& sim, const std::string& deck, const RunLimits& limits = {}) {
  try {
    sim.run(deck, limits);
  } catch (const Error& e) {
    CHECK(e.kind() == Error::Kind::simulator);
    return e.what();
  }
  FAIL("the run succeeded, expected an Error");
  return {};
}

/// The deck path that a failure message names, which must hold the deck.
fs::path kept_deck(const std::string& message) {
  std::smatch m;
  REQUIRE(std::regex_search(message, m, std::regex(R"(\(deck kept at ([^)]+)\)$)")));
  return m[1].str();
}

void check_deck_kept(const std::string& message, const std::string& deck) {
  fs::path path = kept_deck(message);
  CHECK(slurp(path) == deck);
  CHECK_FALSE(fs::exists(path.parent_path() / "out.raw"));  // the rawfile is not kept
  fs::remove_all(path.parent_path());
}

void check_rc(const Vectors& v) {
  const auto& t = v.at("time");
  const auto& out = v.at("v(out)");
  REQUIRE(t.size() > 100);
  REQUIRE(out.size() == t.size());
  REQUIRE(v.at("v(in)").size() == t.size());
  REQUIRE(v.at("i(v1)").size() == t.size());
  CHECK(t.front() == 0.0);
  CHECK(t.back() == Approx(5e-3).epsilon(1e-12));
  double max_error = 0;  // tau = 1 ms; default reltol 1e-3 on a 1 V step
  for (std::size_t k = 0; k < t.size(); ++k) max_error = std::max(max_error, std::abs(out[k] - (1 - std::exp(-t[k] / 1e-3))));
  CHECK(max_error < 1e-3);
}

/// A fake ngspice: a shell script in a fresh directory.
fs::path fake_ngspice(const std::string& body) {
  std::string dir = (fs::temp_directory_path() / "gearpatch-fake-XXXXXX").string();
  REQUIRE(mkdtemp(dir.data()) != nullptr);
  fs::path script = fs::path(dir) / "ngspice";
  std::ofstream(script) << "#!/bin/sh\n" << body << "\n";
  fs::permissions(script, fs::perms::owner_all);
  return script;
}

bool process_gone(pid_t pid) {
  if (kill(pid, 0) != 0) return errno == ESRCH;
  std::string stat = slurp(fmt::format("/proc/{}/stat", pid));  // a zombie is gone too
  auto close = stat.rfind(')');
  return close != std::string::npos && stat.size() > close + 2 && stat[close + 2] == 'Z';
}

/// A behavioural source that switches on an exponential of its own node
/// voltage: no step is small enough once the pulse arrives.
const std::string aborting_deck =
    "timestep too small\n"
    "V1 in 0 PULSE(0 1 0 1p 1p 1u 2u)\n"
    "B1 out 0 V = v(in) > 0.5 ? 1e6*exp(v(out)*100) : 0\n"
    "R1 out 0 1k\n"
    ".tran 1n 10u\n"
    ".end\n";

}  // namespace

TEST_CASE("batch ngspice runs an RC deck and returns its vectors", "[spice]") {
  auto sim = make_batch_ngspice();
  check_rc(sim->run(kRcDeck, {}));
}

TEST_CASE("batch ngspice reads an ASCII rawfile the same way", "[spice]") {
  std::string deck = kRcDeck;
  deck.insert(deck.find(".tran"), ".options filetype=ascii\n");
  check_rc(make_batch_ngspice()->run(deck, {}));
}

TEST_CASE("batch ngspice writes the deck to keep_deck_as on success too", "[spice]") {
  fs::path keep = fs::temp_directory_path() / fmt::format("gearpatch-test-keep-{}.cir", getpid());
  RunLimits limits;
  limits.keep_deck_as = keep.string();
  check_rc(make_batch_ngspice()->run(kRcDeck, limits));
  CHECK(slurp(keep) == kRcDeck);

  std::string message = failure_of(*make_batch_ngspice(), "broken\n.tran 1m\n.end\n", limits);
  CHECK(kept_deck(message) == keep);
  CHECK(slurp(keep) == "broken\n.tran 1m\n.end\n");
  fs::remove(keep);
}

TEST_CASE("a deck ngspice cannot parse gives ngspice's error lines", "[spice]") {
  const std::string deck = "bad tran\nV1 in 0 DC 1\nR1 in 0 1k\n.tran 1m\n.end\n";
  std::string message = failure_of(*make_batch_ngspice(), deck);
  CHECK_THAT(message, Catch::StartsWith("ngspice could not run the deck: Error on line"));
  CHECK_THAT(message, Catch::Contains("TSTOP is invalid, must be greater than zero"));
  CHECK_THAT(message, Catch::Contains("circuit not parsed"));
  check_deck_kept(message, deck);
}

TEST_CASE("a run that aborts with timestep too small names the time and node", "[spice]") {
  const std::string deck = aborting_deck;
  std::string message = failure_of(*make_batch_ngspice(), deck);
  CHECK_THAT(message, Catch::Matches(R"(ngspice aborted: timestep too small at time = [0-9.e+-]+ s \(timestep [0-9.e+-]+ s\): trouble with node "out" \(deck kept at .*\))"));
  check_deck_kept(message, deck);
}

TEST_CASE("a run past its wall-clock limit is killed and reported", "[spice]") {
  RunLimits limits;
  limits.timeout = 1s;
  auto start = std::chrono::steady_clock::now();
  std::string message = failure_of(*make_batch_ngspice(), kEndlessDeck, limits);
  // A lower bound only: how soon the kill lands depends on the machine's load.
  CHECK(std::chrono::steady_clock::now() - start >= 1s);
  CHECK_THAT(message, Catch::StartsWith("ngspice timed out after 1 s"));
  check_deck_kept(message, kEndlessDeck);
}

TEST_CASE("a timeout too long to count in nanoseconds is no instant timeout", "[spice]") {
  RunLimits limits;
  limits.timeout = std::chrono::milliseconds::max();
  check_rc(make_batch_ngspice()->run(kRcDeck, limits));
}

TEST_CASE("a run past its output cap is killed and reported", "[spice]") {
  RunLimits limits;
  limits.max_output_bytes = 200'000;
  std::string message = failure_of(*make_batch_ngspice(), kEndlessDeck, limits);
  CHECK_THAT(message, Catch::StartsWith("ngspice output exceeded the cap of 200000 bytes"));
  check_deck_kept(message, kEndlessDeck);
}

TEST_CASE("a missing ngspice executable gives the install hint", "[spice]") {
  std::string message = failure_of(*make_batch_ngspice("/nonexistent/ngspice"), kRcDeck);
  CHECK_THAT(message, Catch::Contains("ngspice was not found (tried '/nonexistent/ngspice')"));
  CHECK_THAT(message, Catch::Contains("apt-get install ngspice"));
  check_deck_kept(message, kRcDeck);
  // A bare name is looked up in PATH.
  message = failure_of(*make_batch_ngspice("gearpatch-no-such-ngspice"), kRcDeck);
  CHECK_THAT(message, Catch::StartsWith("ngspice was not found (tried 'gearpatch-no-such-ngspice'); "
                                        "install it, e.g. 'apt-get install ngspice'"));
  check_deck_kept(message, kRcDeck);
}

TEST_CASE("ngspice runs with a C numeric locale and batch arguments, no shell", "[spice]") {
  // The fake prints what it was given to stderr and fails, so the message quotes it.
  fs::path fake = fake_ngspice(
      "echo \"args: $*\" >&2\n"
      "echo \"locale: LC_ALL=$LC_ALL LC_NUMERIC=$LC_NUMERIC\" >&2\n"
      "echo \"deck: $(head -n 1 deck.cir)\" >&2\n"
      "exit 5");
  setenv("LC_NUMERIC", "de_DE.UTF-8", 1);
  std::string message = failure_of(*make_batch_ngspice(fake.string()), kRcDeck);
  unsetenv("LC_NUMERIC");
  CHECK_THAT(message, Catch::StartsWith("ngspice failed with exit status 5: "
                                        "args: -b -r out.raw deck.cir / "
                                        "locale: LC_ALL=C LC_NUMERIC=C / "
                                        "deck: rc step response"));
  check_deck_kept(message, kRcDeck);
  fs::remove_all(fake.parent_path());
}

TEST_CASE("a timeout kills ngspice's whole process group", "[spice]") {
  fs::path fake = fake_ngspice("sleep 30 &\necho $! > child.pid\nsleep 30");
  RunLimits limits;
  limits.timeout = 300ms;
  std::string message = failure_of(*make_batch_ngspice(fake.string()), kRcDeck, limits);
  CHECK_THAT(message, Catch::StartsWith("ngspice timed out after 0.3 s"));
  fs::path dir = kept_deck(message).parent_path();
  pid_t grandchild = std::stoi(slurp(dir / "child.pid"));
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i, std::this_thread::sleep_for(20ms)) gone = process_gone(grandchild);
  CHECK(gone);
  fs::remove_all(dir);
  fs::remove_all(fake.parent_path());
}

TEST_CASE("a crashed ngspice and a missing rawfile are failures", "[spice]") {
  fs::path crash = fake_ngspice("echo 'about to crash' >&2\nkill -SEGV $$");
  std::string message = failure_of(*make_batch_ngspice(crash.string()), kRcDeck);
  CHECK_THAT(message, Catch::StartsWith(fmt::format("ngspice was killed by signal {}: about to crash", SIGSEGV)));
  fs::remove_all(kept_deck(message).parent_path());
  fs::remove_all(crash.parent_path());

  fs::path silent = fake_ngspice("echo 'nothing to do' >&2\nexit 0");
  message = failure_of(*make_batch_ngspice(silent.string()), kRcDeck);
  CHECK_THAT(message, Catch::StartsWith("ngspice wrote no rawfile: nothing to do"));
  fs::remove_all(kept_deck(message).parent_path());
  fs::remove_all(silent.parent_path());
}

TEST_CASE("a rawfile cut short by a full disk is a failure though ngspice exits 0", "[spice]") {
  // Two of the three points declared: ngspice's writes failed, its exit status did not.
  fs::path full_disk = fake_ngspice(
      "printf 'Title: t\\nPlotname: Transient Analysis\\nFlags: real\\nNo. Variables: 2\\n"
      "No. Points: 3\\nVariables:\\n\\t0\\ttime\\ttime\\n\\t1\\tv(out)\\tvoltage\\n"
      "Values:\\n0\\t0\\n\\t0\\n1\\t1e-3\\n\\t0.5\\n' > out.raw\nexit 0");
  std::string message = failure_of(*make_batch_ngspice(full_disk.string()), kRcDeck);
  CHECK_THAT(message, Catch::StartsWith("ngspice's output is cut short: its rawfile holds 2 of the 3 points"));
  fs::remove_all(kept_deck(message).parent_path());
  fs::remove_all(full_disk.parent_path());
}

TEST_CASE("a numerical abort is retried once with the fallback deck, a deck error is not", "[spice]") {
  const std::string aborts = aborting_deck;
  const std::string fine = "rc\nV1 in 0 DC 1\nR1 in out 1k\nC1 out 0 1n\n.tran 1u 10u\n.end\n";
  const auto fallback = [&] { return std::optional<std::string>(fine); };
  auto ngspice = make_batch_ngspice();
  std::optional<Retry> retry;
  run_with_retry(*ngspice, aborts, {}, fallback, "the fine deck", retry);
  REQUIRE(retry);
  CHECK_THAT(retry->first_failure, Catch::StartsWith("ngspice aborted: timestep too small"));
  std::optional<Retry> none;
  CHECK_THROWS_WITH(run_with_retry(*ngspice, "broken\n.tran 1m\n.end\n", {}, fallback, "the fine deck", none),
                    Catch::StartsWith("ngspice could not run the deck"));
  CHECK_FALSE(none);
}

TEST_CASE("ngspice console output is classified in ngspice's words", "[spice]") {
  const std::string stats = "Total elapsed time (seconds) = 0.003\n\nTotal DRAM available = 24105.133 MB.\n";
  // The message, and "abort" when ngspice gave up numerically (the retry's cue).
  const auto said = [](const std::optional<NgspiceFailure>& f) {
    return f ? f->message + (f->numerical_abort ? " [abort]" : "") : std::string("(ran)");
  };
  CHECK(said(diagnose_ngspice_failure("Circuit: rc\n" + stats, "", 0)) == "(ran)");
  CHECK(said(diagnose_ngspice_failure(stats,
                                      "Warning: singular matrix:  check node out\n\n"
                                      "doAnalyses: iteration limit reached\n\nrun simulation(s) aborted\n",
                                      0)) ==
        "ngspice aborted the simulation: Warning: singular matrix:  check node out / "
        "doAnalyses: iteration limit reached [abort]");
  CHECK(said(diagnose_ngspice_failure(stats,
                                      "Error: unknown subckt: x1 in out nosuch\n"
                                      "    Simulation interrupted due to error!\n\n"
                                      "Error: there aren't any circuits loaded.\n",
                                      1)) ==
        "ngspice could not run the deck: Error: unknown subckt: x1 in out nosuch / "
        "Error: there aren't any circuits loaded.");
  CHECK(said(diagnose_ngspice_failure("Circuit: rc\nsomething odd happened\n" + stats, "", 1)) ==
        "ngspice failed with exit status 1: something odd happened");
  CHECK(said(diagnose_ngspice_failure(stats, "", 1)) == "ngspice failed with exit status 1: no message");
  CHECK(said(diagnose_ngspice_failure("", "doAnalyses: TRAN:  Timestep too small; time = 1.5e-06, timestep = 1e-20: "
                                          "cause unrecorded.\n", 1)) ==
        "ngspice aborted: timestep too small at time = 1.5e-06 s (timestep 1e-20 s): cause unrecorded. [abort]");
}

TEST_CASE("Vectors::at names a missing vector and lists those present", "[spice]") {
  Vectors v;
  v.data["time"] = {0.0, 1.0};
  v.data["v(out)"] = {2.0, 3.0};
  CHECK(v.at("v(out)")[1] == 3.0);
  try {
    v.at("v(wp)");
    FAIL("no error for a missing vector");
  } catch (const Error& e) {
    CHECK(e.kind() == Error::Kind::simulator);
    CHECK(std::string(e.what()) == "no vector 'v(wp)' in the simulation result (available: time, v(out))");
  }
}

TEST_CASE("the scripted simulator plays back outcomes and records decks", "[spice]") {
  ScriptedSimulator sim;
  Vectors first;
  first.data["time"] = {0.0};
  sim.then_return(first).then_throw(Error("ngspice timed out after 1 s", Error::Kind::simulator));
  RunLimits limits;
  limits.timeout = 7s;
  Simulator& as_interface = sim;

  CHECK(as_interface.run("deck one", limits).at("time") == std::vector<double>{0.0});
  CHECK_THROWS_WITH(as_interface.run("deck two", {}), "ngspice timed out after 1 s");
  CHECK_THROWS_WITH(as_interface.run("deck three", {}), "scripted simulator has no outcome left for run 3");
  CHECK(sim.decks() == std::vector<std::string>{"deck one", "deck two", "deck three"});
  REQUIRE(sim.limits().size() == 3);
  CHECK(sim.limits()[0].timeout == 7s);
  CHECK(sim.pending() == 0);
}
