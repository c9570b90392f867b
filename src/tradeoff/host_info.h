#pragma once
#include <cstdint>
#include <string>

namespace gearpatch::tradeoff {

/// HostInfo: the computer a benchmark ran on (not the analog machine), recorded
/// next to its numbers.
struct HostInfo {
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
HostInfo collect_host_info(const std::string& ngspice = "ngspice");

}  // namespace gearpatch::tradeoff
