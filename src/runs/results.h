#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runs/job_list.h"

namespace gearpatch::runs {

/// What one job left in the run folder: its result, or why there is none.
struct JobOutcome {
  std::size_t index = 0;
  std::string label;
  std::optional<nlohmann::json> result;
  std::string failure;  ///< when there is no result: the job's own reason, or that none was written
};

/// The members every result has, whatever the study: the run id, the job's
/// index and input digest, then either the study's own members or a
/// "failure" (why the job could not run, in the tool's words).
nlohmann::json result_schema(const nlohmann::json& body_properties, const std::vector<std::string>& required);

/// Reads every job's result of a run folder in job order, however the jobs
/// were run (local pool, GNU Parallel, Slurm). The manifest is checked, and
/// every job's inputs against their digests; each result is read as a
/// regular file (no link, FIFO or device), checked against `schema` and
/// must repeat the manifest's run id, its index and its digest. Anything
/// else is an Error (exit 2) naming the file and what is wrong. A missing
/// result is an outcome naming its log (whose text stays out of tables).
std::vector<JobOutcome> collect_results(const RunFolder& folder, const Manifest& manifest,
                                        const nlohmann::json& schema);

/// One result's text checked as collect_results does: Error naming `source`.
nlohmann::json check_result(const std::string& text, const std::string& source, const nlohmann::json& schema,
                            const Manifest& manifest, std::size_t index);

}  // namespace gearpatch::runs
