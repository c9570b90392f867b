#pragma once
#include <string>

namespace gearpatch {

/// Throws Error unless `path` names an image gnuplot can draw (.png or .svg):
/// called before a long run, so a typo does not cost its result.
void check_plot_path(const std::string& path);

/// Draws an image file with gnuplot. `script` is everything after the terminal
/// and output lines, with its data inline (`$name << EOD`). The image is drawn
/// next to `path` and renamed into place, so a failed run leaves no
/// half-written plot. Throws Error for an extension other than .png or .svg,
/// and with gnuplot's own message if it fails.
void draw_with_gnuplot(const std::string& path, int width, int height, const std::string& script);

}  // namespace gearpatch
