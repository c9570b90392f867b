#include <filesystem>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/output_set.h"
#include "scene/random_scene.h"
#include "scene/scene.h"

namespace gearpatch::cli {

int run_random_scenes(const std::vector<std::string>& args) {
  po::options_description options("random-scenes options");
  options.add_options()
      ("seed", po::value<std::uint64_t>()->default_value(1), "the seed: the same seed and index give the same scene")
      ("count", po::value<int>()->default_value(42), "how many scenes (1 … 10000); the features take turns")
      ("out,o", po::value<std::string>(), "the folder to write NAME.ini into (made if missing)");
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch random-scenes [--seed S] [--count N] -o DIR\n\n"
                       "Writes N random, physically plausible scenes, taking turns over the feature\n"
                       "classes frictionless, bearing friction, tooth friction, self-locking, driven,\n"
                       "loaded and zero backlash: inertias 1e-4…10 kg·m² (ratios up to 1e3 either\n"
                       "way), stiffness 10…1e5 N·m/rad, backlash 0…0.2 rad, k 0…1, efficiency 0.3…1;\n"
                       "speeds, torques and run length follow from the contact period. Each file\n"
                       "passes the scene reader. bench/random-scenes.sh verifies a set and prints\n"
                       "the pass rate.",
                       options,
                       {"gearpatch random-scenes --seed 1 --count 42 -o random",
                        "bench/random-scenes.sh 1 42"},
                       vm, false))
    return 0;
  if (vm.count("scene")) throw Error("random-scenes takes no SCENE (see --help)");
  if (!vm.count("out")) throw Error("random-scenes needs -o DIR, the folder to write into");
  const int count = vm["count"].as<int>();
  if (count < 1 || count > 10000) throw Error(fmt::format("--count = {}: must be in [1, 10000]", count));
  const std::filesystem::path folder = vm["out"].as<std::string>();
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw Error(fmt::format("-o {}: cannot make the folder: {}", folder.string(), ec.message()));
  const auto scenes = random_scenes(vm["seed"].as<std::uint64_t>(), count);
  OutputSet outputs;
  for (const auto& s : scenes) {
    const std::string path = (folder / (s.name + ".ini")).string();
    parse_scene(s.text, path);  // a generated scene the reader refuses is a bug here
    outputs.add(s.name, path);
    outputs.stage(s.name, s.text);
  }
  outputs.commit();
  fmt::print(stderr, "{} scenes in {}\n", scenes.size(), folder.string());
  return 0;
}

}  // namespace gearpatch::cli
