#!/usr/bin/env bash
# One name, one meaning: renames files, folders, namespaces and identifiers
# whose names meant two or three things. Run once from the repository root on
# a clean tree, then build, test and commit the result:
#
#   bench/tools/renames.sh && cmake --build build && ctest --test-dir build
#
# It works by pattern only (git mv for files, word-bounded perl substitutions
# for names, include lines and CMake paths), so it applies to a tree that other
# branches have changed since. Before changing anything it checks that every
# source path is there and no target is: a second run stops there, whole. (If
# it stops later, on a pattern it needs that is gone, `git reset --hard`
# undoes the partial run.) A one-off: delete it once applied. Public names stay: command
# names, command-line options, scene keys, JSON keys, ctest entries other than
# the component-spread area, and every output.
#
#   scaling::Patch (scaled settings)  -> ScaledProgram   scaling/scaled_program.h
#   PatchOptions / make_patch         -> ScalingOptions / scale_program
#   src/bench (gearpatch bench)       -> src/tradeoff, gearpatch::tradeoff
#   bench MachineInfo                 -> HostInfo        tradeoff/host_info.h
#   src/figures (the paper's plots)   -> src/paper_plots, gearpatch::paper_plots
#   sweep PointFigures                -> PointMetrics    sweep/point_metrics.h
#   HardwareFigures / IdealFigures    -> DatasheetConstants / IdealConstants
#   src/tolerance (component spread)  -> src/component_spread, ctest area too
#   common/option_error.h's INI part  -> common/ini_reader.{h,cc}
set -euo pipefail

die() { echo "renames.sh: $*" >&2; exit 1; }
note() { echo "renames.sh: $*" >&2; }

root=$(git rev-parse --show-toplevel 2>/dev/null) || die "not inside a git repository"
[ "$PWD" = "$root" ] || die "run from the repository root ($root)"
[ -z "$(git status --porcelain --untracked-files=no)" ] || die "the tree has uncommitted changes; commit or stash them first"
self=$(git ls-files --full-name "${BASH_SOURCE[0]}" 2>/dev/null || true)

# ---------------------------------------------------------------- files

# move OLD NEW: git mv, failing clearly when OLD is missing or NEW exists.
move() {
  [ -e "$1" ] || die "missing source path '$1' (already renamed, or moved by another change?)"
  [ ! -e "$2" ] || die "target '$2' exists already"
  mkdir -p "$(dirname "$2")"
  git mv "$1" "$2"
}

# move_folder OLD NEW: every tracked file of OLD into NEW (the folder itself then goes).
move_folder() {
  [ -d "$1" ] || die "missing source folder '$1'"
  [ ! -e "$2" ] || die "target folder '$2' exists already"
  git mv "$1" "$2"
}

# The INI reader out of common/option_error.* (checked above: the version
# this split was written for).
split_ini_reader() {
  local h=src/common/option_error.h cc=src/common/option_error.cc
  git mv "$cc" src/common/ini_reader.cc
  cat > src/common/ini_reader.cc <<'EOF'
#include "common/ini_reader.h"

#include <boost/program_options/options_description.hpp>
#include <boost/program_options/parsers.hpp>
#include <boost/program_options/value_semantic.hpp>
#include <sstream>

#include "common/error.h"
#include "common/option_error.h"

namespace gearpatch {
namespace po = boost::program_options;

std::vector<boost::program_options::option> parse_ini_options(const std::string& text,
                                                              const std::map<std::string, std::string>& keys,
                                                              const std::string& source) {
  po::options_description description;
  for (const auto& [key, help] : keys) description.add_options()(key.c_str(), po::value<std::string>(), help.c_str());
  std::istringstream in(text);
  try {
    return po::parse_config_file(in, description, true).options;
  } catch (const po::error& e) {
    throw Error(source + ": " + option_error_message(e));
  }
}

}  // namespace gearpatch
EOF
  cat > src/common/ini_reader.h <<'EOF'
#pragma once
#include <boost/program_options/option.hpp>
#include <map>
#include <string>
#include <vector>

namespace gearpatch {

/// The INI reader of scene files and machine profiles: the `key = value`
/// lines of an INI text, each key one of `keys` (key → help) or marked
/// unregistered for the caller to name; a line Boost cannot read is an Error
/// "SOURCE: message".
std::vector<boost::program_options::option> parse_ini_options(const std::string& text,
                                                              const std::map<std::string, std::string>& keys,
                                                              const std::string& source);

}  // namespace gearpatch
EOF
  cat > "$h" <<'EOF'
#pragma once
#include <boost/program_options/errors.hpp>
#include <string>

namespace gearpatch {

/// Boost.Program_options' message for `e`, built safely. Boost fills the
/// user's text into its message template until no placeholder is left, so
/// text that itself holds one ("x%canonical_option%") loops for ever; here
/// each '%' of the user's text is shown as '?'.
std::string option_error_message(const boost::program_options::error& e);

}  // namespace gearpatch
EOF
  cat > "$cc" <<'EOF'
#include "common/option_error.h"

#include <algorithm>

namespace gearpatch {
namespace po = boost::program_options;

namespace {

/// A copy of the error whose substituted values hold no '%'.
class DefusedError : public po::error_with_option_name {
 public:
  explicit DefusedError(const po::error_with_option_name& e) : po::error_with_option_name(e) {
    for (auto& [placeholder, value] : m_substitutions) std::replace(value.begin(), value.end(), '%', '?');
    for (auto& [placeholder, from_to] : m_substitution_defaults)
      std::replace(from_to.second.begin(), from_to.second.end(), '%', '?');
  }
};

}  // namespace

std::string option_error_message(const po::error& e) {
  if (const auto* named = dynamic_cast<const po::error_with_option_name*>(&e))
    return DefusedError(*named).what();
  return e.what();
}

}  // namespace gearpatch
EOF
  git add "$h" "$cc" src/common/ini_reader.h src/common/ini_reader.cc
}

# Every source there and no target yet, before anything changes: a second
# run, or a tree where another change moved one of these, stops here whole.
for path in src/scaling/{patch.h,patch.cc,patch_format.cc,patch_parts.h,solved_patch.cc} \
            src/bench/{bench.h,bench.cc,bench_report.h,bench_report.cc,machine_info.h,machine_info.cc} \
            src/figures/paper_figures.{h,cc} src/sweep/point_figures.{h,cc} src/tolerance \
            src/common/option_error.{h,cc}; do
  [ -e "$path" ] || die "missing source path '$path' (already renamed, or moved by another change?); nothing changed"
done
for path in src/scaling/scaled_program.h src/tradeoff src/paper_plots src/sweep/point_metrics.h \
            src/component_spread src/common/ini_reader.{h,cc}; do
  [ ! -e "$path" ] || die "target '$path' exists already; nothing changed"
done
# The INI reader's split writes option_error.* whole, so only from the version
# it was made for (the files' git blobs); else it is one to redo by hand.
[ "$(git hash-object src/common/option_error.h)" = 0d183220b6cfa0809f45dce974191d12d457a654 ] &&
  [ "$(git hash-object src/common/option_error.cc)" = 3f0198abeab22821255b7223b3bf39f860ee67fa ] ||
  die "src/common/option_error.{h,cc} changed since the split was written: split the INI reader out by hand; nothing changed"

move src/scaling/patch.h src/scaling/scaled_program.h
move src/scaling/patch.cc src/scaling/scaled_program.cc
move src/scaling/patch_format.cc src/scaling/scaled_program_format.cc
move src/scaling/patch_parts.h src/scaling/scaled_program_parts.h
move src/scaling/solved_patch.cc src/scaling/solved_program.cc
move_folder src/bench src/tradeoff
move src/tradeoff/bench.h src/tradeoff/tradeoff.h
move src/tradeoff/bench.cc src/tradeoff/tradeoff.cc
move src/tradeoff/bench_report.h src/tradeoff/tradeoff_report.h
move src/tradeoff/bench_report.cc src/tradeoff/tradeoff_report.cc
move src/tradeoff/machine_info.h src/tradeoff/host_info.h
move src/tradeoff/machine_info.cc src/tradeoff/host_info.cc
move_folder src/figures src/paper_plots
move src/paper_plots/paper_figures.h src/paper_plots/paper_plots.h
move src/paper_plots/paper_figures.cc src/paper_plots/paper_plots.cc
move src/sweep/point_figures.h src/sweep/point_metrics.h
move src/sweep/point_figures.cc src/sweep/point_metrics.cc
move_folder src/tolerance src/component_spread
split_ini_reader

# ---------------------------------------------------------------- text

# The tracked text files the names live in (this script excluded; recorded
# results and fuzz corpora keep what they recorded).
text_files() {
  git ls-files -z -- src tests bench fuzz cmake CMakeLists.txt docs CONTRIBUTING.md templates |
    grep -zv -e '^bench/results/' -e '^fuzz/corpus/' -e '^tools/renames\.sh$' -e '^bench/tools/renames\.sh$' \
      ${self:+-e "^$self\$"} |
    xargs -0 grep -lIZ '' -- 2>/dev/null || true
}
code_files() { text_files | grep -zE '\.(h|cc|cpp)$' || true; }

# sub FILES... -- PERL: the substitution over each file, in place.
each() {
  local script=$1
  shift
  [ $# -gt 0 ] || return 0
  perl -0777 -pi -e "$script" -- "$@"
}

mapfile -d '' all < <(text_files)
mapfile -d '' code < <(code_files)

# Paths, in includes, CMake, docs and comments.
each '
  s{\bscaling/patch_format\.cc\b}{scaling/scaled_program_format.cc}g;
  s{\bscaling/patch_parts\.h\b}{scaling/scaled_program_parts.h}g;
  s{\bscaling/solved_patch\.cc\b}{scaling/solved_program.cc}g;
  s{\bscaling/patch\.(h|cc)\b}{scaling/scaled_program.$1}g;
  s{(?<![\w/.])patch_format\.cc\b}{scaled_program_format.cc}g;
  s{(?<![\w/.])patch_parts\.h\b}{scaled_program_parts.h}g;
  s{(?<![\w/.])solved_patch\.cc\b}{solved_program.cc}g;
  s{(?<![\w/.-])patch\.(h|cc)\b(?!\.)}{scaled_program.$1}g;
  s{\b(src/)?bench/bench_report\.(h|cc)\b}{$1tradeoff/tradeoff_report.$2}g;
  s{\b(src/)?bench/bench\.(h|cc)\b}{$1tradeoff/tradeoff.$2}g;
  s{\b(src/)?bench/machine_info\.(h|cc)\b}{$1tradeoff/host_info.$2}g;
  s{\b(src/)?bench/pareto\.(h|cc)\b}{$1tradeoff/pareto.$2}g;
  s{(?<![\w/.])machine_info\.(h|cc)\b}{host_info.$1}g;
  s{\bsrc/bench\b}{src/tradeoff}g;
  s{\b(src/)?figures/paper_figures\.(h|cc)\b}{$1paper_plots/paper_plots.$2}g;
  s{(?<![\w/.])paper_figures\.(h|cc)\b}{paper_plots.$1}g;
  s{\bsrc/figures\b}{src/paper_plots}g;
  s{\bpoint_figures\.(h|cc)\b}{point_metrics.$1}g;
  s{\bsrc/tolerance\b}{src/component_spread}g;
  s{(?<=")tolerance/(?=\w+\.(?:h|cc)")}{component_spread/}g;
  s{(?<=[\s`(])tolerance/(?=\w+\.(?:h|cc)\b)}{component_spread/}g;
  s{(?<=#include ")bench/}{tradeoff/}g;
  s{(?<=#include ")figures/}{paper_plots/}g;
' "${all[@]}"

# Identifiers, in code and in the comments and docs that name them.
each '
  s{\bPatchOptions\b}{ScalingOptions}g;
  s{\bPatch\b}{ScaledProgram}g;
  s{\bmake_patch\b}{scale_program}g;
  s{\bsolve_patch\b}{solve_program}g;
  s{\bpaper_patch\b}{paper_program}g;
  s{\bpatch_of\b}{program_of}g;
  s{\bpatch_options\b}{scaling_options}g;
  s{\bpatch_delta\b}{program_delta}g;
  s{\bgearpatch::bench\b}{gearpatch::tradeoff}g;
  s{(?<![\w:])bench::(?=\w)}{tradeoff::}g;
  s{\bMachineInfo\b}{HostInfo}g;
  s{\bcollect_machine_info\b}{collect_host_info}g;
  s{\bgearpatch::figures\b}{gearpatch::paper_plots}g;
  s{(?<![\w:])figures::(?=\w)}{paper_plots::}g;
  s{\bPointFigures\b}{PointMetrics}g;
  s{\bpoint_figures\b}{point_metrics}g;
  s{\bfigures_from_json\b}{metrics_from_json}g;
  s{\bbalance_figures\b}{balance_metrics}g;
  s{\bHardwareFigures\b}{DatasheetConstants}g;
  s{\bIdealFigures\b}{IdealConstants}g;
  s{^(// -+ fixed )figures$}{${1}constants}mg;
  s{\(generic: the TL071 figures above\)}{(generic: the TL071 values above)}g;
  s{\bgearpatch::tolerance\b}{gearpatch::component_spread}g;
  s{(?<![\w:.])tolerance::(?=\w)}{component_spread::}g;
  s{\[tolerance\]}{[component_spread]}g;
' "${code[@]}" templates/README.md templates/hardware/opamp.mustache

# The INI reader's users include its header.
for f in $(grep -lw parse_ini_options "${code[@]}" | grep -v '^src/common/ini_reader\.'); do
  if grep -qw option_error_message "$f"; then
    perl -pi -e 's{^#include "common/option_error\.h"\n}{#include "common/ini_reader.h"\n$&}' "$f"
  else
    perl -pi -e 's{^#include "common/option_error\.h"$}{#include "common/ini_reader.h"}' "$f"
  fi
  grep -q '^#include "common/ini_reader.h"' "$f" || die "$f: could not point its include at common/ini_reader.h"
done

# The scaled program's own variables, in the files that hold one and no
# machine wiring but patch_on_machine's (string literals, the output, stay).
# A file that reads a member called patch (x.patch, x->patch), or a header
# that declares one, keeps its names: the member may be a machine patch, and
# its other readers are elsewhere.
mapfile -t program_files < <(grep -lwE 'ScaledProgram|scale_program' "${code[@]}" |
  grep -vP '^src/patching/(?!machine_patch\.)|^src/cli/patch_command\.cc$|^tests/test_patch(ing|_sheet)\.cpp$' |
  perl -ne 'chomp; my $f = $_; open my $in, "<", $f or die "$f: $!"; local $/; my $t = <$in>;
    $t =~ s{"(?:[^"\\\n]|\\.)*"}{""}g;
    next if $t =~ /(?:\.|->)patch\b/ or ($f =~ /\.h$/ and $t =~ /\bpatch\s*;/);
    print "$f\n";')
each '
  s{("(?:[^"\\\n]|\\.)*"|'"'"'(?:[^'"'"'\\\n]|\\.)'"'"')|(?<!gearpatch )(?<!can )\bpatch(_?)\b(?! sheet| from)}{defined $1 ? $1 : "program$2"}ge;
' "${program_files[@]}"

# The benchmark's host (the word "machine" is the analog computer).
mapfile -t host_files < <(grep -lw HostInfo "${code[@]}"; grep -l 'tradeoff::' "${code[@]}"; ls src/tradeoff/*.cc)
each '
  s{\bHostInfo machine;}{HostInfo host;}g;
  s{\b(r|o|evil|result|options)\.machine\b(?=\.|;| =)}{$1.host}g;
' $(printf '%s\n' "${host_files[@]}" | sort -u)

# Build and layering rules: the tradeoff library, the component-spread area.
perl -pi -e '
  s{\bgearpatch_bench_lib\b}{gearpatch_tradeoff}g;
  s{\bBENCH_LIBRARY_SOURCES\b}{TRADEOFF_SOURCES}g;
  s{/src/\(bench\|cli\)/}{/src/(tradeoff|cli)/}g;
  s{but the benchmark \(src/tradeoff/}{but the speed/accuracy trade-off (src/tradeoff/}g;
  s{\btolerance\b}{component_spread}g;  # the word is only the ctest area here (its lists and tags)
' CMakeLists.txt
perl -pi -e '
  s{"bench" IN_LIST}{"tradeoff" IN_LIST}g;
  s{\bincludes bench/}{includes tradeoff/}g;
  s{\(bench is not}{(tradeoff is not}g;
' cmake/check_layering.cmake
grep -q '"tradeoff" IN_LIST' cmake/check_layering.cmake || die "cmake/check_layering.cmake: the bench/ rule was not found"
perl -pi -e 's{includes `bench/`}{includes `tradeoff/`}g' CONTRIBUTING.md

# ---------------------------------------------------------------- what each name means

# doc FILE DECL TEXT: TEXT as the first lines of the /// block above the first
# line matching DECL (a new block if there is none); stops if DECL is missing.
doc() {
  DECL=$2 TEXT=$3 perl -0777 -pi -e '
    my ($decl, $text) = ($ENV{DECL}, $ENV{TEXT});
    $text =~ s{^}{/// }mg;
    s{((?:^[ \t]*///.*\n)*)(^.*$decl)}{$text\n$1$2}m or die "no line matching $decl\n";
  ' "$1" || die "$1: no declaration matching '$2'"
}
# redoc FILE DECL TEXT: TEXT in place of the /// block above DECL.
redoc() {
  DECL=$2 TEXT=$3 perl -0777 -pi -e '
    my ($decl, $text) = ($ENV{DECL}, $ENV{TEXT});
    $text =~ s{^}{/// }mg;
    s{(?:^[ \t]*///.*\n)*(^.*$decl)}{$text\n$1}m or die "no line matching $decl\n";
  ' "$1" || die "$1: no declaration matching '$2'"
}

doc src/scaling/scaled_program.h '^struct ScaledProgram \{' \
'ScaledProgram: the scene scaled onto the machine, the numbers `gearpatch
settings` prints (circuit::build_circuit turns it into blocks,
patching::MachinePatch wires those onto a machine).'
doc src/tradeoff/tradeoff.h '^namespace gearpatch::tradeoff \{' \
'tradeoff: the speed/accuracy trade-off of the ngspice settings that `gearpatch
bench` measures (bench/ at the top holds the microbenchmarks and scripts).'
redoc src/tradeoff/host_info.h '^struct HostInfo \{' \
'HostInfo: the computer a benchmark ran on (not the analog machine), recorded
next to its numbers.'
doc src/paper_plots/paper_plots.h '^namespace gearpatch::paper_plots \{' \
'paper_plots: the paper'"'"'s Bild 5a-c and 6a-c redrawn from the example scenes.'
doc src/sweep/point_metrics.h '^struct PointMetrics \{' \
'PointMetrics: the figures of merit of one sweep point (its JSON key is
"figures").'
doc src/component_spread/component_draw.h '^namespace gearpatch::component_spread \{' \
'component_spread: how the spread of real components (tolerances, offsets)
moves a hardware run: draws, error budget, Monte Carlo, offset check (verify'"'"'s
tolerance is the pass band, a different thing).'
if grep -q '^struct DatasheetConstants' src/circuit/block_library.cc; then
  redoc src/circuit/block_library.cc '^struct DatasheetConstants \{' \
'DatasheetConstants: the hardware level'"'"'s component values from datasheets
(templates/README.md lists them).'
else
  note "src/circuit/block_library.cc has no struct DatasheetConstants; its comment is left as it is"
fi

# Docs that describe the layout.
perl -pi -e '
  s{^src/component_spread +}{src/component_spread  }; s{^src/paper_plots +}{src/paper_plots  };
  s{^src/tradeoff +}{src/tradeoff  };
  s{Pareto fronts, machine info \(own library\)}{Pareto fronts, host info (own library)};
  s{(maxima \(6\.11, 6\.12\), time scale .*), the patch$}{$1, the scaled program};
' docs/layout.md

git add -A -- src tests bench fuzz cmake CMakeLists.txt docs CONTRIBUTING.md templates
note "done; build, run ctest and compare the outputs before committing"
