// Fuzz target: the ngspice rawfile reader, ASCII and binary, on damaged bytes.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/error.h"
#include "spice/rawfile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    for (const auto& plot : gearpatch::spice::read_rawfile({reinterpret_cast<const char*>(data), size}))
      for (const auto& column : plot.columns)
        if (column.size() != plot.points()) __builtin_trap();  // the reader promises equal columns
  } catch (const gearpatch::Error&) {
  }
  return 0;
}
