#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gearpatch {

/// One run of an external tool that turns input files into one output file
/// (gnuplot's plots, Graphviz's pictures): the one place that runs such a
/// tool, so that every tool is bounded alike and fails with one message.
struct ToolRun {
  std::string program;       ///< "gnuplot", looked up in PATH; also names it in messages
  std::string install_hint;  ///< "apt-get install gnuplot-nox", for a missing program
  std::string option;        ///< the option the output is for ("--plot"), first in a failure message
  std::vector<std::string> args;
  std::vector<std::pair<std::string, std::string>> inputs;  ///< file name, contents: written before the run
  std::string output;        ///< the file the tool writes, a fixed name in its folder
  std::chrono::milliseconds timeout{std::chrono::minutes(1)};
  std::uintmax_t max_output_bytes = std::uintmax_t{64} << 20;
};

/// Runs the tool as a child (common/process.h) in a private scratch folder
/// holding its inputs, log and output, and returns the output's bytes. Throws
/// Error (input) "<option>: <program> failed (exit status N): <its stderr>"
/// (or "(killed by signal N)") when it fails or writes no output.
std::string run_tool(const ToolRun& run);

/// The image format ("png" or "svg", by the extension of `path`) a tool is
/// to draw for `option`, checked before a long run together with the tool:
/// Error naming the option and path for another extension or a missing
/// `program` (called `what` in the message).
std::string tool_image_format(const std::string& path, const std::string& option, const std::string& program,
                              const std::string& what, const std::string& install_hint);

}  // namespace gearpatch
