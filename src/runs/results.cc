#include "runs/results.h"

#include <fmt/format.h>

#include "common/error.h"
#include "runs/json_schema.h"
#include "runs/run_files.h"

namespace gearpatch::runs {
using nlohmann::json;

json result_schema(const json& body_properties, const std::vector<std::string>& required) {
  json properties = body_properties;
  properties["run"] = {{"type", "string"}, {"pattern", "[0-9a-f]{32}"}};
  properties["index"] = {{"type", "integer"}, {"minimum", 0}};
  properties["digest"] = {{"type", "string"}, {"pattern", "[0-9a-f]{40}"}};
  properties["failure"] = {{"type", "string"}, {"maxLength", 4096}};
  return {{"type", "object"},
          {"required", {"run", "index", "digest"}},
          {"properties", properties},
          {"additionalProperties", false},
          {"body_required", required}};
}

json check_result(const std::string& text, const std::string& source, const json& schema, const Manifest& manifest,
                  std::size_t index) {
  const json r = parse_checked(text, schema, source);
  if (r["run"] != manifest.run)
    throw Error(fmt::format("{}: a result of run {}, not of this run folder's run {}", source,
                            r["run"].get<std::string>(), manifest.run));
  if (r["index"].get<std::size_t>() != index)
    throw Error(fmt::format("{}: the result of job {}, not of job {}", source, r["index"].dump(), index));
  if (r["digest"] != manifest.digests.at(index))
    throw Error(fmt::format("{}: computed from other inputs than job {} has (its digest differs)", source, index));
  if (!r.contains("failure"))
    for (const json& name : schema.value("body_required", json::array()))
      if (!r.contains(name.get<std::string>()))
        throw Error(fmt::format("{}: /: lacks \"{}\"", source, name.get<std::string>()));
  return r;
}

std::vector<JobOutcome> collect_results(const RunFolder& folder, const Manifest& manifest, const json& schema) {
  folder.check_inputs(manifest);
  std::vector<JobOutcome> outcomes;
  for (std::size_t i = 0; i < manifest.labels.size(); ++i) {
    JobOutcome o;
    o.index = i;
    o.label = manifest.labels[i];
    const auto path = folder.result_path(i);
    if (!exists_at_all(path)) {
      o.failure = fmt::format("no result; its log: {}", folder.log_path(i).string());
    } else {
      json r = check_result(read_run_file(path, most_input_bytes), path.string(), schema, manifest, i);
      if (r.contains("failure")) o.failure = printable(r["failure"].get<std::string>());
      else o.result = std::move(r);
    }
    outcomes.push_back(std::move(o));
  }
  return outcomes;
}

}  // namespace gearpatch::runs
