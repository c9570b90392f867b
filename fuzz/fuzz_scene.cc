// Fuzz target: the scene parser. Any text must parse or throw gearpatch::Error;
// every other exception, crash, hang or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    gearpatch::parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.ini");
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
