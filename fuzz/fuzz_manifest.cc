// Fuzz target: a run folder's manifest reader and the study schemas behind
// it. Any text must be taken or throw gearpatch::Error; every other
// exception, crash, hang or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "runs/job_list.h"
#include "sweep/sweep_study.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const gearpatch::runs::Manifest m =
        gearpatch::runs::parse_manifest(std::string(reinterpret_cast<const char*>(data), size), "manifest.json");
    if (m.study.value("kind", "") == "sweep") {
      const gearpatch::sweep::SweepStudy s = gearpatch::sweep::study_from_json(m.study, "manifest.json");
      gearpatch::sweep::check_jobs(s, m, "manifest.json");
    }
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
