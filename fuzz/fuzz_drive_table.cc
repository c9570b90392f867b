// Fuzz target: the drive table reader and the profile built from it. Any
// text must parse or throw gearpatch::Error; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "model/drive_profile.h"
#include "scene/drive_table.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const gearpatch::DriveProfile profile(
        gearpatch::parse_drive_table(std::string(reinterpret_cast<const char*>(data), size), "table.csv"));
    profile.torque(0.5);
    profile.next_breakpoint(0.5);
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
