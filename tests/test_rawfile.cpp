// Tests of the ngspice rawfile reader: small files built here byte by byte,
// real files written by ngspice, and random damage to a real file.
#include <catch2/catch.hpp>

#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "spice/rawfile.h"
#include "support.h"

namespace fs = std::filesystem;
using gearpatch::Error;
using gearpatch::spice::Plot;
using gearpatch::spice::read_rawfile;

namespace {

using Points = std::vector<std::vector<double>>;  // points[k][variable]

std::string header(const std::string& plotname, std::size_t declared_points,
                   const std::string& flags = "real", const std::string& extra = "") {
  return fmt::format(
      "Title: golden\nDate: Thu Jan  1 00:00:00  2026\n{}Plotname: {}\nFlags: {}\n"
      "No. Variables: 3\nNo. Points: {:<8}\nVariables:\n"
      "\t0\ttime\ttime\n\t1\tV(IN)\tvoltage\n\t2\tv(out)\tvoltage\n",
      extra, plotname, flags, declared_points);
}

std::string binary_plot(const Points& points, std::size_t declared, const std::string& extra = "") {
  std::string out = header("Transient Analysis", declared, "real", extra) + "Binary:\n";
  for (const auto& point : points) {
    for (double v : point) out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  return out;
}

std::string ascii_plot(const Points& points, std::size_t declared, const std::string& extra = "") {
  std::string out = header("Transient Analysis", declared, "real", extra) + "Values:\n";
  for (std::size_t k = 0; k < points.size(); ++k) {
    out += fmt::format("{}", k);
    for (std::size_t j = 0; j < points[k].size(); ++j) out += fmt::format("{}\t{:.15e}\n", j == 0 ? "\t" : "", points[k][j]);
  }
  return out;
}

const Points kPoints = {{0.0, 1.0, 0.0}, {1e-3, 1.0, 0.632}, {2e-3, 1.0, 0.8647}};

void check_golden_plot(const Plot& plot, std::size_t points) {
  REQUIRE(plot.variables.size() == 3);
  CHECK(plot.variables[0].name == "time");
  CHECK(plot.variables[1].name == "v(in)");  // lower-cased
  CHECK(plot.variables[1].type == "voltage");
  REQUIRE(plot.columns.size() == 3);
  REQUIRE(plot.points() == points);
  for (std::size_t k = 0; k < points; ++k) {
    for (std::size_t j = 0; j < 3; ++j) CHECK(plot.columns[j][k] == kPoints[k][j]);
  }
}

/// Expects read_rawfile to throw gearpatch::Error of kind simulator whose
/// message contains `part`.
void check_rejected(const std::string& bytes, const std::string& part) {
  try {
    read_rawfile(bytes);
    FAIL("accepted a malformed rawfile, expected an error containing: " << part);
  } catch (const Error& e) {
    CHECK(e.kind() == Error::Kind::simulator);
    CHECK_THAT(e.what(), Catch::Contains(part));
  }
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

constexpr const char* kRcDeck = gearpatch::testing::rc_step_deck;

/// Runs the real ngspice on the RC deck and returns the rawfile it wrote.
std::string real_rc_rawfile(bool ascii) {
  std::string dir = (fs::temp_directory_path() / "gearpatch-rawtest-XXXXXX").string();
  REQUIRE(mkdtemp(dir.data()) != nullptr);
  std::ofstream(fs::path(dir) / "rc.cir") << kRcDeck;
  std::string command = fmt::format("cd '{}' && LC_ALL=C SPICE_ASCIIRAWFILE={} ngspice -b -r rc.raw rc.cir >log.txt 2>&1",
                                    dir, ascii ? 1 : 0);
  int status = std::system(command.c_str());
  std::string bytes = slurp(fs::path(dir) / "rc.raw");
  fs::remove_all(dir);
  REQUIRE(status == 0);
  REQUIRE(!bytes.empty());
  return bytes;
}

const std::vector<double>& column(const Plot& plot, const std::string& name) {
  for (std::size_t i = 0; i < plot.variables.size(); ++i) {
    if (plot.variables[i].name == name) return plot.columns[i];
  }
  FAIL("no vector " << name);
  throw;  // unreachable: FAIL throws
}

}  // namespace

TEST_CASE("binary rawfile: header fields and float64 data, point after point", "[spice]") {
  auto plots = read_rawfile(binary_plot(kPoints, 3));
  REQUIRE(plots.size() == 1);
  CHECK(plots[0].title == "golden");
  CHECK(plots[0].name == "Transient Analysis");
  CHECK(plots[0].flags == "real");
  check_golden_plot(plots[0], 3);
}

TEST_CASE("ASCII rawfile: index then one value per line", "[spice]") {
  auto plots = read_rawfile(ascii_plot(kPoints, 3));
  REQUIRE(plots.size() == 1);
  check_golden_plot(plots[0], 3);
}

TEST_CASE("rawfile with two plots: operating point then transient", "[spice]") {
  Points op = {{0.0, 1.0, 1.0}};
  SECTION("binary") {
    auto plots = read_rawfile(binary_plot(op, 1) + binary_plot(kPoints, 3));
    REQUIRE(plots.size() == 2);
    CHECK(plots[0].points() == 1);
    CHECK(plots[0].columns[2][0] == 1.0);
    check_golden_plot(plots[1], 3);
  }
  SECTION("ASCII") {
    auto plots = read_rawfile(ascii_plot(op, 1) + ascii_plot(kPoints, 3));
    REQUIRE(plots.size() == 2);
    CHECK(plots[0].points() == 1);
    check_golden_plot(plots[1], 3);
  }
}

TEST_CASE("rawfile header keys the reader does not know are skipped", "[spice]") {
  const std::string extra = "Command: ngspice-44.2, Build Mon Jan 1\nOption: something new\n";
  check_golden_plot(read_rawfile(binary_plot(kPoints, 3, extra)).at(0), 3);
  check_golden_plot(read_rawfile(ascii_plot(kPoints, 3, extra)).at(0), 3);
}

TEST_CASE("rawfile flags 'real unpadded' are accepted, complex data are refused", "[spice]") {
  std::string unpadded = binary_plot(kPoints, 3);
  unpadded.replace(unpadded.find("Flags: real"), 11, "Flags: real unpadded");
  auto plots = read_rawfile(unpadded);
  CHECK(plots[0].flags == "real unpadded");
  check_golden_plot(plots[0], 3);

  std::string complex = ascii_plot(kPoints, 3);
  complex.replace(complex.find("Flags: real"), 11, "Flags: complex");
  check_rejected(complex, "line 4: complex data are not supported");
}

TEST_CASE("rawfile of an aborted run: No. Points 0, the points present are read", "[spice]") {
  check_golden_plot(read_rawfile(binary_plot(kPoints, 0)).at(0), 3);
  check_golden_plot(read_rawfile(ascii_plot(kPoints, 0)).at(0), 3);
  // Aborted before the first point: an empty plot, not an error.
  auto empty = read_rawfile(binary_plot({}, 0));
  REQUIRE(empty.size() == 1);
  CHECK(empty[0].points() == 0);
  CHECK(empty[0].columns.size() == 3);
}

TEST_CASE("rawfile cut inside a point: the partial last point is dropped", "[spice]") {
  SECTION("binary, declared count larger than the data") {
    std::string bytes = binary_plot(kPoints, 3);
    bytes.resize(bytes.size() - 12);  // third point has 1.5 of 3 values
    check_golden_plot(read_rawfile(bytes).at(0), 2);
  }
  SECTION("binary, declared 0") {
    std::string bytes = binary_plot(kPoints, 0);
    bytes.resize(bytes.size() - 20);
    check_golden_plot(read_rawfile(bytes).at(0), 2);
  }
  SECTION("ASCII, cut inside a number") {
    std::string bytes = ascii_plot(kPoints, 0);
    bytes.resize(bytes.size() - 10);  // last value "8.647000000000000e-01" cut to "8.64700000000"
    check_golden_plot(read_rawfile(bytes).at(0), 2);
  }
  SECTION("ASCII, cut after a complete line inside a point") {
    std::string bytes = ascii_plot(kPoints, 3);
    bytes.resize(bytes.rfind('\n', bytes.size() - 2) + 1);  // third point lacks v(out)
    check_golden_plot(read_rawfile(bytes).at(0), 2);
  }
}

TEST_CASE("a plot with fewer points than its header declares is cut short", "[spice]") {
  using gearpatch::spice::check_complete;
  for (const bool binary : {true, false}) {
    INFO((binary ? "binary" : "ASCII"));
    std::string bytes = binary ? binary_plot(kPoints, 3) : ascii_plot(kPoints, 3);
    const Plot whole = read_rawfile(bytes).at(0);
    CHECK(whole.declared_points == 3);
    CHECK_NOTHROW(check_complete(whole));
    CHECK_NOTHROW(check_complete(read_rawfile(binary ? binary_plot(kPoints, 0) : ascii_plot(kPoints, 0)).at(0)));
    bytes.resize(bytes.size() - (binary ? 24 : 46));  // the last point is gone
    const Plot cut = read_rawfile(bytes).at(0);
    REQUIRE(cut.points() == 2);
    try {
      check_complete(cut);
      FAIL("a cut-short plot passed as complete");
    } catch (const Error& e) {
      CHECK(e.kind() == Error::Kind::simulator);
      CHECK_THAT(e.what(), Catch::Contains("cut short: its rawfile holds 2 of the 3 points"));
    }
  }
}

TEST_CASE("malformed rawfiles are refused with the place and what was expected", "[spice]") {
  const std::string ascii = ascii_plot(kPoints, 3);
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string s = ascii;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  check_rejected("", "rawfile is empty");
  check_rejected("\n\n", "rawfile is empty");
  check_rejected("garbage without a colon\n", "line 1: expected 'Key: value'");
  check_rejected(ascii.substr(0, ascii.find("Variables:\n")), "file ends in a plot header");
  check_rejected(edited("No. Variables: 3", "No. Variables: three"), "line 5: No. Variables must be a whole number");
  check_rejected(edited("No. Points: 3", "No. Points: -3"), "line 6: No. Points must be a whole number");
  check_rejected(edited("\t1\tV(IN)\tvoltage", "\t7\tV(IN)\tvoltage"), "line 9: expected variable 1");
  check_rejected(edited("\t2\tv(out)\tvoltage\n", ""), "line 10: expected variable 2");
  check_rejected(edited("No. Variables: 3\n", ""), "'Variables:' comes before 'No. Variables:'");
  check_rejected("Title: t\nNo. Variables: 0\nNo. Points: 1\nVariables:\nBinary:\n12345678", "line 5: No. Variables is 0");
  check_rejected(edited("\t6.320000000000000e-01", "\t6.32x"), "line 17: expected a number, got '6.32x'");
  check_rejected(edited("1\t\t1.0", "5\t\t1.0"), "line 15: expected point index 1, got '5'");
  // A point cut short in the middle of the file, not at its end.
  std::string short_point = ascii.substr(0, ascii.rfind('\n', ascii.size() - 2) + 1);
  check_rejected(short_point + ascii, "point 2 has 2 of 3 values");
  // Binary data must not be taken for the next plot's header.
  std::string binary = binary_plot(kPoints, 3);
  check_rejected(binary + "\x01\x02 trailing junk", fmt::format("byte {}: expected 'Key: value'", binary.size()));
}

TEST_CASE("real ngspice rawfiles of an RC step match the analytic solution", "[spice]") {
  const std::string binary = real_rc_rawfile(false);
  const std::string ascii = real_rc_rawfile(true);
  REQUIRE(binary.find("Binary:\n") != std::string::npos);
  REQUIRE(ascii.find("Values:\n") != std::string::npos);
  auto from_binary = read_rawfile(binary);
  auto from_ascii = read_rawfile(ascii);
  REQUIRE(from_binary.size() == 1);
  REQUIRE(from_ascii.size() == 1);
  const Plot& b = from_binary[0];
  const Plot& a = from_ascii[0];
  CHECK(b.name == "Transient Analysis");
  REQUIRE(b.points() > 100);
  REQUIRE(a.points() == b.points());

  const auto& t = column(b, "time");
  const auto& v = column(b, "v(out)");
  CHECK(t.front() == 0.0);
  CHECK(t.back() == Approx(5e-3).epsilon(1e-12));
  // tau = R C = 1 ms; ngspice's default reltol 1e-3 on a 1 V step: 1 mV suffices.
  double max_error = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (k > 0) REQUIRE(t[k] > t[k - 1]);
    max_error = std::max(max_error, std::abs(v[k] - (1 - std::exp(-t[k] / 1e-3))));
  }
  CHECK(max_error < 1e-3);
  CHECK(column(b, "v(in)").back() == 1.0);
  CHECK(column(b, "i(v1)").front() == Approx(-1e-3));

  // The ASCII file prints 16 significant digits of the same run.
  for (std::size_t j = 0; j < b.columns.size(); ++j) {
    CHECK(a.variables[j].name == b.variables[j].name);
    for (std::size_t k = 0; k < b.points(); ++k) {
      REQUIRE(a.columns[j][k] == Approx(b.columns[j][k]).epsilon(1e-14).margin(1e-300));
    }
  }
}

TEST_CASE("a real rawfile cut or damaged at random either parses or throws Error", "[spice]") {
  std::mt19937_64 rng(20260101);
  for (bool ascii : {false, true}) {
    const std::string original = real_rc_rawfile(ascii);
    int parsed = 0, refused = 0;
    const int rounds = ascii ? 1500 : 3000;
    for (int round = 0; round < rounds; ++round) {
      std::string bytes = original;
      // Cut in a third of the rounds, damage bytes in the rest (header bytes often).
      if (round % 3 == 0) {
        bytes.resize(std::uniform_int_distribution<std::size_t>(0, bytes.size())(rng));
      } else {
        const std::size_t span = round % 2 ? 600 : bytes.size();
        for (int n = std::uniform_int_distribution<int>(1, 8)(rng); n > 0; --n) {
          std::size_t at = std::uniform_int_distribution<std::size_t>(0, span - 1)(rng);
          bytes[at] = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
        }
      }
      try {
        for (const Plot& plot : read_rawfile(bytes)) {
          REQUIRE(plot.columns.size() == plot.variables.size());
          for (const auto& c : plot.columns) REQUIRE(c.size() == plot.points());
        }
        ++parsed;
      } catch (const Error& e) {
        REQUIRE(e.kind() == Error::Kind::simulator);
        ++refused;
      }
    }
    INFO((ascii ? "ASCII" : "binary") << ": parsed " << parsed << ", refused " << refused);
    CHECK(parsed > rounds / 10);
    CHECK(refused > rounds / 10);
  }
}
