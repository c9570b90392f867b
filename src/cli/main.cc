// gearpatch: gear drive → analog computer program → ngspice → verified.
#include <clocale>
#include <cstdio>
#include <exception>
#include <fmt/format.h>
#include <string>
#include <string_view>
#include <vector>

#include "cli/command.h"
#include "common/error.h"
#include "common/notices.h"
#include "scene/scene.h"

namespace {

void print_usage() {
  std::printf(
      "gearpatch: turns the physical data of a gear drive (two inertias, an elastic\n"
      "coupling with damping, backlash, bearing and tooth friction, self-locking)\n"
      "into an analog computer program after Klittich (1966): potentiometer settings\n"
      "with amplitude and time scaling, and the circuit as an ngspice netlist; runs\n"
      "ngspice and checks the circuit against a reference model of the same equations.\n\n"
      "usage: gearpatch <command> SCENE [options]      (gearpatch <command> --help)\n\n"
      "commands:\n");
  for (const auto& c : gearpatch::cli::commands()) std::printf("  %-10s %s\n", c.name, c.summary);
  std::printf(
      "\n  --help-scene  list every key a scene file may hold\n"
      "  --version     print gearpatch's version\n\n"
      "Outputs: -o/--out FILE for a command's main output, --json FILE for JSON;\n"
      "- is stdout (with --json -, the main output goes to stderr).\n\n"
      "exit status: 0 success (verify: pass), 1 verify failed, 2 bad input or usage,\n"
      "3 the simulator failed (missing, aborted, timed out, NaN or cut-short output),\n"
      "4 internal error (a bug: please report it).\n\n"
      "examples:\n"
      "  gearpatch verify scenes/bild5b.ini --plot bild5b.svg\n"
      "  gearpatch netlist scenes/bild5a.ini --level hardware -o bild5a.cir\n");
}

void print_scene_keys() {
  std::printf("Scene files are INI (Boost.Program_options syntax), SI units, # comments:\n\n");
  for (const auto& [key, help] : gearpatch::scene_keys())
    std::printf("  %-34s %s\n", key.c_str(), help.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::setlocale(LC_ALL, "C");
  gearpatch::set_notice_sink([](std::string_view text) { std::fwrite(text.data(), 1, text.size(), stderr); });
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_usage();
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("gearpatch %s\n", GEARPATCH_VERSION);
    return 0;
  }
  if (args[0] == "--help-scene") {
    print_scene_keys();
    return 0;
  }
  for (const auto& command : gearpatch::cli::commands()) {
    if (args[0] != command.name) continue;
    try {
      return command.run({args.begin() + 1, args.end()});
    } catch (const gearpatch::Error& e) {
      const bool internal = e.kind() == gearpatch::Error::Kind::internal;
      std::fprintf(stderr, "gearpatch %s: %s%s\n", command.name, internal ? "internal error: " : "", e.what());
      return gearpatch::exit_status(e.kind());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpatch %s: internal error: %s\n", command.name, e.what());
      return gearpatch::exit_status(gearpatch::Error::Kind::internal);
    }
  }
  std::fprintf(stderr, "gearpatch: unknown command '%s' (see gearpatch --help)\n", args[0].c_str());
  return 2;
}
