#include "sweep/sweep_outputs.h"

#include <cstdio>
#include <fmt/format.h>

#include "common/error.h"
#include "common/json_text.h"
#include "common/gnuplot.h"
#include "common/notices.h"

namespace gearpatch::sweep {

SweepOutputs::SweepOutputs(const SweepOutputPaths& paths) : paths_(paths) {
  if (!paths.table.empty()) set_.add("--out", paths.table);
  if (!paths.json.empty()) set_.add("--json", paths.json);
  if (!paths.csv.empty()) set_.add("--csv", paths.csv);
  if (!paths.plot.empty()) {
    set_.add("--plot", paths.plot);
    plot_format_ = plot_format(paths.plot, "--plot");
  }
  if (!paths.figures_plot.empty()) {
    set_.add("--figures-plot", paths.figures_plot);
    figures_format_ = plot_format(paths.figures_plot, "--figures-plot");
  }
}

void SweepOutputs::write(const SweepTable& table) {
  const std::string text = to_text(table);
  std::vector<std::string> warnings;
  if (set_.has("--out")) set_.stage("--out", text);
  if (set_.has("--json")) set_.stage("--json", json_text(to_json(table), 1));
  if (set_.has("--csv")) set_.stage("--csv", to_csv(table));
  const auto draw = [&](const std::string& option, const std::string& format, auto&& plot) {
    if (!set_.has(option)) return;
    try {
      set_.stage(option, plot(table, format));
    } catch (const Error& e) {
      warnings.push_back(fmt::format("{} {}: not written: {}", option, set_.path(option), e.what()));
    }
  };
  draw("--plot", plot_format_, overlay_plot);
  draw("--figures-plot", figures_format_, figures_plot);
  set_.commit();
  if (!set_.has("--out")) notice(text);
  for (const std::string& w : warnings) notice("gearpatch sweep: warning: " + w + "\n");
}

namespace {

/// Error unless a point's result holds its own values and a trace whose
/// columns are as long as its times, as the table and the plots read them.
void check_point_result(const nlohmann::json& result, const Assignment& point, const std::vector<Signal>& signals,
                        const std::string& source) {
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [key, value] : point) values[key] = value;
  if (result["values"] != values) throw Error(fmt::format("{}: its values are not its point's", source));
  const nlohmann::json& trace = result["trace"];
  for (Signal s : signals)
    if (!trace.contains(to_string(s)) || trace[to_string(s)].size() != trace["t"].size())
      throw Error(fmt::format("{}: /trace/{}: missing or not as long as /trace/t", source, to_string(s)));
}

}  // namespace

SweepTable read_sweep(const runs::RunFolder& folder) {
  const runs::Manifest manifest = folder.manifest();
  const std::string source = (folder.dir() / "manifest.json").string();
  SweepTable table{study_from_json(manifest.study, source), {}};
  check_jobs(table.study, manifest, source);
  table.points = runs::collect_results(folder, manifest, result_schema());
  const std::vector<Assignment> points = table.study.points();
  for (const runs::JobOutcome& o : table.points)
    if (o.result) check_point_result(*o.result, points[o.index], table.study.options.signals, folder.result_path(o.index).string());
  return table;
}

int merge_and_write(const runs::RunFolder& folder, SweepOutputs& outputs) {
  const SweepTable table = read_sweep(folder);
  outputs.write(table);
  if (table.failed() > 0) return 3;
  for (const runs::JobOutcome& o : table.points)
    if (o.result->contains("verify") && !(*o.result)["verify"]["passed"].get<bool>()) return 1;
  return 0;
}

}  // namespace gearpatch::sweep
