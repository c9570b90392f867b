#pragma once
#include <string>
#include <string_view>

namespace gearpatch {

/// The image format gnuplot draws for `path` ("png" or "svg", by its
/// extension), checked before a long run together with gnuplot itself:
/// Error naming `option` for another extension or a missing gnuplot.
std::string plot_format(const std::string& path, const std::string& option = "--plot");

/// `text` as a gnuplot string literal, so that it is drawn and never run:
/// single-quoted (no backslash escapes, no `@` macros, no backquote commands
/// in gnuplot), a quote doubled, and line breaks and other control characters
/// (which would end the command) turned into spaces. Mark the text
/// `noenhanced` where it is drawn to see it literally.
std::string gnuplot_string(std::string_view text);

/// Text for a line of an inline data block (`$data << EOD`) as a quoted
/// field: no line break (which could end the block) and no double quote.
std::string gnuplot_data_label(std::string_view text);

/// Draws an image with gnuplot and returns its bytes. `script` is everything
/// after the terminal and output lines, with its data inline; gnuplot runs as
/// a child (common/process.h) in a private scratch folder, with its script,
/// log and image there. Throws Error with gnuplot's own message if it fails.
std::string draw_with_gnuplot(const std::string& format, int width, int height, const std::string& script);

}  // namespace gearpatch
