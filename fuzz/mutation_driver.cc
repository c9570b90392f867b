// A seeded mutation driver for the fuzz targets where libFuzzer is missing
// (a compiler other than clang). It takes libFuzzer's command line, so one
// script runs either: the seeds are the files in the corpus folders, each run
// first as-is, then mutated by a generator seeded with -seed (deterministic:
// the same seed and corpus give the same inputs). Unknown -flags are ignored.
//
//   fuzz_scene [-seed=N] [-runs=N] [-max_total_time=S] [-timeout=S]
//              [-dict=FILE] [-artifact_prefix=P] CORPUS_DIR_OR_FILE...
//
// A sanitizer report, an uncaught exception or an input running longer than
// -timeout writes that input to P + "crash-N" or "timeout-N" and ends with a
// non-zero status, as libFuzzer does.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define GEARPATCH_HAVE_ASAN 1
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

// The input under test and where to save it, for the handlers of a finding.
std::string current_input;
std::string crash_path, timeout_path;

/// Writes the input under test to `path` with async-signal-safe calls only.
void save_current_input(const std::string& path) {
  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  const char* p = current_input.data();
  std::size_t left = current_input.size();
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n <= 0) break;
    p += n, left -= static_cast<std::size_t>(n);
  }
  ::close(fd);
  const char note[] = "mutation driver: the failing input is in ";
  (void)!::write(2, note, sizeof note - 1);
  (void)!::write(2, path.c_str(), path.size());
  (void)!::write(2, "\n", 1);
}

[[maybe_unused]] void on_sanitizer_death() { save_current_input(crash_path); }
void on_terminate() {
  save_current_input(crash_path);
  std::abort();
}
void on_alarm(int) {
  save_current_input(timeout_path);
  const char note[] = "mutation driver: timeout\n";
  (void)!::write(2, note, sizeof note - 1);
  ::_exit(70);
}

/// xorshift64*: small, fast and the same everywhere.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed ? seed : 0x9E3779B97F4A7C15ull) {}
  std::uint64_t next() {
    state_ ^= state_ >> 12, state_ ^= state_ << 25, state_ ^= state_ >> 27;
    return state_ * 0x2545F4914F6CDD1Dull;
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }

 private:
  std::uint64_t state_;
};

/// Reads a libFuzzer dictionary: one "token" per line (name= before it is
/// optional), with \\, \" and \xNN escapes.
std::vector<std::string> read_dictionary(const std::string& path) {
  std::vector<std::string> tokens;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const auto open = line.find('"'), close = line.rfind('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos || close <= open) continue;
    std::string token;
    for (std::size_t i = open + 1; i < close; ++i) {
      if (line[i] != '\\' || i + 1 >= close) {
        token += line[i];
      } else if (line[i + 1] == 'x' && i + 3 < close) {
        token += static_cast<char>(std::stoi(line.substr(i + 2, 2), nullptr, 16)), i += 3;
      } else {
        token += line[++i];
      }
    }
    tokens.push_back(token);
  }
  return tokens;
}

/// One random edit of `input`: a bit flip, a special byte, a cut, a copied
/// range, a dictionary token, or a splice with another seed.
void mutate(std::string& input, Random& rng, const std::vector<std::string>& tokens,
            const std::vector<std::string>& seeds) {
  static const char special[] = {'\n', '\r', '\t', ' ', '=', '[', ']', '#', '+', '-', '.', ':',
                                 '0',  '1',  '9',  'e', 'E', '*', '\0', '\x7f', '\xff', '\xef'};
  const std::size_t at = rng.below(input.size() + 1);
  switch (rng.below(6)) {
    case 0:
      if (!input.empty()) input[rng.below(input.size())] ^= static_cast<char>(1u << rng.below(8));
      break;
    case 1:
      if (!input.empty()) input[rng.below(input.size())] = special[rng.below(sizeof special)];
      break;
    case 2:
      input.erase(at, 1 + rng.below(16));
      break;
    case 3:
      if (!input.empty()) {
        const std::size_t from = rng.below(input.size());
        input.insert(at, input.substr(from, 1 + rng.below(64)));
      }
      break;
    case 4:
      if (!tokens.empty()) input.insert(at, tokens[rng.below(tokens.size())]);
      break;
    default: {
      const std::string& other = seeds[rng.below(seeds.size())];
      input = input.substr(0, at) + other.substr(rng.below(other.size() + 1));
    }
  }
}

void run(const std::string& input, unsigned timeout_s) {
  current_input = input;
  if (timeout_s) ::alarm(timeout_s);
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  if (timeout_s) ::alarm(0);
}

/// The command line: libFuzzer's flags this driver knows, and the seed paths.
struct Flags {
  std::uint64_t seed = 1, runs = 0;
  double max_time = 0;
  unsigned timeout_s = 0;
  std::size_t max_len = 1 << 16;
  std::string prefix;
  std::vector<std::string> tokens, seed_paths;
};

Flags parse_flags(int argc, char** argv) {
  Flags f;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* flag) { return arg.substr(std::strlen(flag)); };
    if (arg.rfind("-seed=", 0) == 0) f.seed = std::stoull(value("-seed="));
    else if (arg.rfind("-runs=", 0) == 0) f.runs = std::stoull(value("-runs="));
    else if (arg.rfind("-max_total_time=", 0) == 0) f.max_time = std::stod(value("-max_total_time="));
    else if (arg.rfind("-timeout=", 0) == 0) f.timeout_s = static_cast<unsigned>(std::stoul(value("-timeout=")));
    else if (arg.rfind("-max_len=", 0) == 0) f.max_len = std::stoull(value("-max_len="));
    else if (arg.rfind("-artifact_prefix=", 0) == 0) f.prefix = value("-artifact_prefix=");
    else if (arg.rfind("-dict=", 0) == 0) f.tokens = read_dictionary(value("-dict="));
    else if (arg.rfind("-", 0) == 0) continue;  // a libFuzzer flag this driver does not know
    else if (fs::is_directory(arg)) {
      for (const auto& entry : fs::directory_iterator(arg))
        if (entry.is_regular_file()) f.seed_paths.push_back(entry.path().string());
    } else if (fs::is_regular_file(arg)) {
      f.seed_paths.push_back(arg);
    }
  }
  std::sort(f.seed_paths.begin(), f.seed_paths.end());  // directory order is not stable
  return f;
}

std::vector<std::string> load_seeds(const std::vector<std::string>& paths) {
  std::vector<std::string> seeds;
  for (const auto& path : paths) {
    std::ifstream in(path, std::ios::binary);
    seeds.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (seeds.empty()) seeds.emplace_back();
  return seeds;
}

}  // namespace

int main(int argc, char** argv) {
  const Flags f = parse_flags(argc, argv);
  const std::vector<std::string> seeds = load_seeds(f.seed_paths);
  crash_path = f.prefix + "crash-" + std::to_string(f.seed);
  timeout_path = f.prefix + "timeout-" + std::to_string(f.seed);
#ifdef GEARPATCH_HAVE_ASAN
  __sanitizer_set_death_callback(on_sanitizer_death);
#endif
  std::set_terminate(on_terminate);
  ::signal(SIGALRM, on_alarm);

  for (const auto& s : seeds) run(s, f.timeout_s);
  Random rng(f.seed);
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t done = 0;
  for (; f.runs == 0 || done < f.runs; ++done) {
    if (f.max_time > 0 && done % 64 == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= f.max_time)
      break;
    if (f.runs == 0 && f.max_time <= 0) break;  // neither limit: the seeds only, as to rerun a finding
    std::string input = seeds[rng.below(seeds.size())];
    for (std::size_t edits = 1 + rng.below(8); edits > 0; --edits) mutate(input, rng, f.tokens, seeds);
    if (input.size() > f.max_len) input.resize(f.max_len);
    run(input, f.timeout_s);
  }
  std::fprintf(stderr, "mutation driver: %zu seeds, %llu mutated inputs, no finding\n", seeds.size(),
               static_cast<unsigned long long>(done));
  return 0;
}
