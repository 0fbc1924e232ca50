// Line plots rendered as SVG by gnuplot (Debian's gnuplot-nox). Each plot NAME is three files in
// one directory: NAME.dat (the data, one block per series), NAME.gp (the gnuplot script, which
// reads NAME.dat and writes NAME.svg by relative names, so it can be rerun in place) and NAME.svg.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace boxpile {

// The k-th colour (cyclic) for series that are not one engine's: a pair of engines, a solver's
// loop. An engine's series take engine_colour(name) (reference/registry.hpp) instead.
std::string plot_colour(int k);

struct PlotSeries {
  // Points are filled circles, Triangles filled triangles, Crosses crosses.
  enum class Style { Line, Dashed, Dotted, DashDot, Points, Triangles, Crosses, LinePoints };
  std::string title;
  std::vector<double> x, y;
  Style style = Style::Line;
  // "#rrggbb": engine_colour() for an engine's series (series of one engine share it),
  // plot_colour() for others.
  std::string colour = plot_colour(0);
  // gnuplot's dash type of a Line or LinePoints series (1 solid, 2 dashed, 3 dotted, 4 dash-dot,
  // 5 dash-dot-dot): series of one colour told apart.
  int dash = 1;
  // Whether the key lists the series (series drawn alike for every engine can leave it to one
  // entry of PlotSpec::key that names the style).
  bool in_key = true;
};

struct PlotSpec {
  std::string name;  // file stem
  std::string title, xlabel, ylabel;
  bool log_y = false;
  // On a log axis, values below this are drawn at it (a difference of exactly 0 has no logarithm).
  double log_floor = 1e-12;
  std::optional<double> hline;  // a dotted horizontal line (a threshold)
  std::string hline_title;
  std::vector<PlotSeries> series;
  bool log_x = false;  // values below log_floor are drawn at it, as on y
  // A log axis with values of exactly 0 says, in a note on the plot, where they are drawn.
  // Entries of the key alone (no data): a style's meaning, e.g. "translational (dashed)" in grey.
  std::vector<PlotSeries> key{};
};

// The key sits below the plot, at most this many entries a row, and the picture grows by a row's
// height for each row, so that the plot keeps the whole width (a key at the side took up to half
// of it) and its height.
inline constexpr int kKeyColumns = 4;
inline constexpr int kPlotWidth = 900, kPlotHeight = 420, kKeyRowHeight = 20;

class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes NAME.dat and NAME.gp into `dir`. Series without points are left out of the script.
void write_plot_files(const std::filesystem::path& dir, const PlotSpec& spec);

// Runs gnuplot on NAME.gp in `dir`, making NAME.svg; throws PlotError with gnuplot's message when
// it fails or cannot be started.
void render_plot(const std::filesystem::path& dir, const std::string& name);

// Whether a gnuplot executable is on the PATH.
bool gnuplot_available();

// Writes every plot's files into `dir` and renders them when gnuplot is available. Returns the
// names rendered; what went wrong (no gnuplot, a plot gnuplot refused) is added to `notes`.
std::vector<std::string> write_plots(const std::filesystem::path& dir, const std::vector<PlotSpec>& plots,
                                     std::vector<std::string>& notes);

}  // namespace boxpile
