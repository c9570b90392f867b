// Fuzz target: the machine profile parser. Any text must parse or throw
// gearpatch::Error; every other exception, crash, hang or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "machine/machine_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    gearpatch::parse_machine_profile(std::string(reinterpret_cast<const char*>(data), size), "fuzz.ini");
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
