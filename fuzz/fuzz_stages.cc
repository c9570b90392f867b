// Fuzz target: the stage parser and the reduction it feeds, whose frequency
// sweep must end on any stages the parser accepts.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "model/stage_reduction.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto stages =
        gearpatch::parse_stages(std::string(reinterpret_cast<const char*>(data), size), "fuzz.ini");
    gearpatch::reduce_stages(stages);
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
