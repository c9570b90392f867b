// Fuzz target: a run folder's result reader (a sweep point's result, the
// schema, the run id, index and digest checks). Any text must be taken or
// throw gearpatch::Error; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "runs/results.h"
#include "sweep/sweep_study.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gearpatch::runs::Manifest m;
  m.run = "0123456789abcdef0123456789abcdef";
  m.labels = {"gear.restitution=0.5"};
  m.digests = {"0123456789abcdef0123456789abcdef01234567"};
  try {
    gearpatch::runs::check_result(std::string(reinterpret_cast<const char*>(data), size), "results/0000.json",
                                  gearpatch::sweep::result_schema(), m, 0);
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
