// The hardware verdict: judged at the tolerance alone, the error budget a
// prediction printed beside the measurement, the Monte Carlo's yield the
// draws that pass every check verify makes. Real ngspice throughout.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "common/atomic_file.h"
#include "support.h"

using namespace gearpatch;

namespace {

const std::string kBinary = GEARPATCH_BINARY;

/// Every signal's measured error from verify's --json.
double worst_measured(const nlohmann::json& j) {
  double worst = 0;
  for (const auto& [signal, error] : j.at("measurement").at("signals").items())
    worst = std::max(worst, error.get<double>());
  return worst;
}

}  // namespace

TEST_CASE("a hardware run beyond the tolerance but within its predicted budget fails, the budget printed beside it",
          "[component_spread][slow]") {
  testing::TempFolder dir("verdict-budget");
  // THE ANALOG THING with the spring unswitched: bild6c's X' stage offset acts in free flight
  std::string profile = read_file(testing::source_path("machines/the-analog-thing.ini"));
  const auto key = profile.find("switched_spring = true");
  REQUIRE(key != std::string::npos);
  profile.replace(key, 22, "switched_spring = false");
  write_file_atomically(dir / "unswitched.ini", profile);
  std::string output;
  const int status = testing::run_command(kBinary + " verify " + testing::scene_path("bild6c") +
                                              " --level hardware --machine " + dir / "unswitched.ini" +
                                              " --budget -j 2 --json " +
                                              dir / "v.json" + " --out " + dir / "v.txt",
                                          output);
  const nlohmann::json j = testing::read_json(dir / "v.json");
  const std::string report = read_file(dir / "v.txt");
  INFO(report);
  // The premise: the circuit errs beyond the hardware default and within the
  // budget's worst prediction (the tolerance a budget-judged verdict would take).
  REQUIRE(j.at("tolerance").get<double>() == 0.02);
  REQUIRE(worst_measured(j) > 0.02);
  REQUIRE(worst_measured(j) <= j.at("prediction").at("budget").at("worst").get<double>());
  CHECK(status == 1);
  CHECK(j.at("verdict") == "fail");
  CHECK(j.at("passed") == false);
  // Prediction and measurement as fields of their own, per signal.
  for (const auto& [signal, p] : j.at("prediction").at("signals").items()) {
    CAPTURE(signal);
    CHECK(p.at("measured") == j.at("measurement").at("signals").at(signal));
    CHECK(p.at("predicted").get<double>() == j.at("prediction").at("budget").at("predicted").at(signal).get<double>());
  }
  // The report: tolerance in its first line, the prediction beside the measurement, one verdict at the end.
  CHECK(report.substr(0, report.find('\n')).find("tolerance 2 % of full scale") != std::string::npos);
  CHECK_THAT(report, Catch::Contains("predicted %") && Catch::Contains("measured %"));
  for (const auto& [signal, p] : j.at("prediction").at("signals").items())
    CHECK_THAT(report, Catch::Contains(p.at("within").get<bool>() ? "measured within the predicted"
                                                                  : "worse than predicted: something the budget "
                                                                    "does not model (" + signal));
  CHECK(report.find("FAIL\n") > report.find("prediction beside the measurement"));
  CHECK_THAT(report, !Catch::Contains("met its error budget") && !Catch::Contains("PASS"));
}

TEST_CASE("a deck whose torque potentiometer is 10 % off fails at the hardware default whatever the budget says",
          "[component_spread]") {
  testing::TempFolder dir("verdict-detuned");
  std::string output;
  const std::string scene = testing::scene_path("bild5b");
  REQUIRE(testing::run_command(kBinary + " netlist " + scene + " --level hardware --machine classic -o " +
                                   dir / "bild5b.cir",
                               output) == 0);
  // The deck as generated passes at 2 %: what fails below is the potentiometer.
  const std::string verify = kBinary + " verify " + scene + " --machine classic --deck ";
  REQUIRE(testing::run_command(verify + dir / "bild5b.cir", output) == 0);
  std::string deck = read_file(dir / "bild5b.cir");
  const std::regex alpha13(R"(\.param alpha13=([0-9.eE+-]+))");
  std::smatch m;
  REQUIRE(std::regex_search(deck, m, alpha13));
  deck = std::regex_replace(deck, alpha13, fmt::format(".param alpha13={:.9g}", 0.9 * std::stod(m[1])));
  write_file_atomically(dir / "detuned.cir", deck);
  CHECK(testing::run_command(verify + dir / "detuned.cir", output) == 1);
  CHECK_THAT(output, Catch::Contains("tolerance 2 % of full scale") && Catch::Contains("FAIL"));
  // With the budget beside it: the verdict and the exit status stay, and the
  // edit is something the budget (of the generated deck) does not model.
  CHECK(testing::run_command(verify + dir / "detuned.cir --budget -j 2 --json " + dir / "v.json", output) == 1);
  const nlohmann::json j = testing::read_json(dir / "v.json");
  CHECK(j.at("verdict") == "fail");
  CHECK(j.at("tolerance").get<double>() == 0.02);
  REQUIRE(!j.at("prediction").is_null());
  CHECK(j.at("prediction").at("measured_within") == false);
  CHECK_THAT(output, Catch::Contains("the budget is of the generated deck") &&
                         Catch::Contains("worse than predicted: something the budget does not model"));
}

TEST_CASE("the Monte Carlo's yield is the share of draws that pass every check, never above a per-check yield",
          "[component_spread]") {
  testing::TempFolder dir("verdict-yield");
  std::string output;
  const int n = 6;
  REQUIRE(testing::run_command(kBinary + " monte-carlo " + testing::scene_path("bild5b") +
                                   fmt::format(" --machine the-analog-thing -n {} --seed 3 -j 2 --run-dir ", n) +
                                   dir / "run" + " --json " + dir / "mc.json" + " --out " + dir / "mc.txt",
                               output) == 0);
  const nlohmann::json j = testing::read_json(dir / "mc.json");
  REQUIRE(j.at("completed") == n);
  // Each draw's own result, as verify judged it.
  int all_pass = 0;
  for (int i = 0; i < n; ++i) {
    const nlohmann::json r = testing::read_json(dir / fmt::format("run/results/{:04d}.json", i));
    bool every = r.at("passed").get<bool>();
    for (const auto& [check, passed] : r.at("checks").items()) every = every && passed.get<bool>();
    CHECK(every == r.at("passed").get<bool>());
    all_pass += every;
  }
  const double yield = j.at("yield").get<double>();
  CHECK(yield == Approx(static_cast<double>(all_pass) / n));
  for (const auto& s : j.at("signals")) {
    CAPTURE(s.at("signal"));
    CHECK(yield <= s.at("yield").get<double>());
  }
  REQUIRE(!j.at("checks").empty());
  for (const auto& c : j.at("checks")) {
    CAPTURE(c.at("check"));
    CHECK(yield <= c.at("yield").get<double>());
  }
  const std::string table = read_file(dir / "mc.txt");
  CHECK_THAT(table, Catch::Contains(fmt::format("{} of {} completed draws pass every check", all_pass, n)));
}
