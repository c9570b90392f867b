#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sweep/point_metrics.h"

/// paper_plots: the paper's Bild 5a-c and 6a-c redrawn from the example scenes.
namespace gearpatch::paper_plots {

/// One of the paper's figures of section 7 and the example scene that redraws it.
struct PaperFigure {
  std::string bild;        ///< "5b"
  std::string scene;       ///< file stem in the scene folder: "bild5b"
  std::string paper_says;  ///< what section 7 says the figure shows
};

/// Bild 5a–c (no friction; k = 1, 0.5, 0) and Bild 6a–c (k = 1 with secondary
/// bearing friction; tooth friction η_z = 0.8; a self-locking spindle).
const std::vector<PaperFigure>& paper_figures();

/// A redrawn figure: its image and the numbers it shows.
struct Redrawn {
  std::string image;
  nlohmann::json numbers;  ///< figure, scene, caption, closed-form and measured mean, restitution, losses, verify
};

/// Redraws `figure` from the scene file at `scene_path` in the paper's
/// manner: φ̇p and φ̇s over time after the initial primary speed, the exact
/// reference and the ideal circuit (ngspice) together, the momentum mean
/// φ̇p0·Θp/(Θp+Θs) marked for Bild 5, the scene's values in the caption.
Redrawn redraw(const PaperFigure& figure, const std::string& scene_path, const std::string& format);

}  // namespace gearpatch::paper_plots
