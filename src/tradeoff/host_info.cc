#include "tradeoff/host_info.h"

#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fstream>
#include <regex>
#include <sys/utsname.h>
#include <unistd.h>

namespace gearpatch::tradeoff {
namespace {

std::string command_output(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  pclose(pipe);
  return out;
}

/// The value after "key<blanks>:" on the first line of `path` that starts with key.
std::string proc_field(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const auto begin = line.find_first_not_of(" \t", colon + 1);
    return begin == std::string::npos ? "" : line.substr(begin);
  }
  return "";
}

std::string ngspice_version(const std::string& ngspice) {
  const std::string banner = command_output("'" + ngspice + "' -v 2>&1 </dev/null");
  std::smatch m;
  std::string version = "unknown";
  static const std::regex pattern(R"((ngspice-[0-9][0-9A-Za-z.+-]*))");
  if (std::regex_search(banner, m, pattern)) version = m[1];
  std::string package = command_output("dpkg-query -W -f='${Version}' ngspice 2>/dev/null");
  if (!package.empty() && package.find('\n') == std::string::npos)
    version += " (package " + package + ")";
  return version;
}

}  // namespace

HostInfo collect_host_info(const std::string& ngspice) {
  HostInfo info;
  info.nproc = static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
  info.cpu_model = proc_field("/proc/cpuinfo", "model name");
  if (info.cpu_model.empty()) info.cpu_model = "unknown";
  const std::string mem = proc_field("/proc/meminfo", "MemTotal");  // "24683656 kB"
  try {
    info.memory_bytes = std::stoull(mem) * 1024;
  } catch (...) {
    info.memory_bytes = 0;
  }
  info.ngspice_version = ngspice_version(ngspice);
  info.date = fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::time(nullptr)));
#if defined(__clang__)
  info.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  info.compiler = "g++ " __VERSION__;
#else
  info.compiler = "unknown";
#endif
#if defined(__OPTIMIZE__)
  info.optimized = true;
#endif
  info.revision = command_output("git describe --always --dirty 2>/dev/null");
  while (!info.revision.empty() && std::isspace(static_cast<unsigned char>(info.revision.back())))
    info.revision.pop_back();
  if (info.revision.empty()) info.revision = "unknown";
  struct utsname u;
  info.os = uname(&u) == 0 ? fmt::format("{} {} {}", u.sysname, u.release, u.machine) : "unknown";
  return info;
}

}  // namespace gearpatch::tradeoff
