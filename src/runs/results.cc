#include "runs/results.h"

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"

namespace gearpatch::runs {

std::vector<JobOutcome> collect_results(const RunFolder& folder) {
  const nlohmann::json manifest = folder.manifest();
  std::vector<JobOutcome> outcomes;
  const nlohmann::json& labels = manifest.at("jobs");
  for (std::size_t i = 0; i < labels.size(); ++i) {
    JobOutcome o;
    o.index = i;
    o.label = labels[i].get<std::string>();
    const std::string path = folder.result_path(i).string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      std::string log;
      try {
        log = read_file(folder.log_path(i).string());
      } catch (const Error&) {
      }
      while (!log.empty() && log.back() == '\n') log.pop_back();
      const auto cut = log.rfind('\n');
      o.failure = fmt::format("no result {}{}{}", path, log.empty() ? "" : ": ",
                              cut == std::string::npos ? log : log.substr(cut + 1));
    } else {
      try {
        o.result = nlohmann::json::parse(read_file(path));
      } catch (const nlohmann::json::exception& e) {
        o.failure = fmt::format("{}: unreadable result: {}", path, e.what());
      }
    }
    outcomes.push_back(std::move(o));
  }
  return outcomes;
}

}  // namespace gearpatch::runs
