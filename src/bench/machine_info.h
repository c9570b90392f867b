#pragma once
#include <cstdint>
#include <string>

namespace gearpatch::bench {

/// The machine a benchmark ran on, recorded next to its numbers.
struct MachineInfo {
  int nproc = 0;                 ///< online processors
  std::string cpu_model;         ///< /proc/cpuinfo "model name" (or "unknown")
  std::uint64_t memory_bytes = 0;  ///< /proc/meminfo MemTotal
  std::string ngspice_version;   ///< banner of `ngspice -v`, plus the package version if known
  std::string date;              ///< UTC, ISO 8601
  std::string compiler;          ///< the compiler that built gearpatch
  bool optimized = false;        ///< built with optimisation (__OPTIMIZE__)
  std::string os;                ///< uname: system, release, machine
  std::string revision;          ///< `git describe --always --dirty` of the working directory, if any
};

/// Reads it from /proc, uname, `ngspice -v` and the build's compiler macros.
/// Never throws: anything it cannot find is "unknown".
MachineInfo collect_machine_info(const std::string& ngspice = "ngspice");

}  // namespace gearpatch::bench
