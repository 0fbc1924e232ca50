#include "boxpile/validation/core/plots.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace boxpile {
namespace {

namespace fs = std::filesystem;

// Colours of series that are no engine's: darker or duller than the engines' (registry.cpp), so
// that a pair's line is not taken for an engine's.
constexpr std::array<const char*, 6> kPalette = {"#332288", "#117733", "#88CCEE", "#AA4499",
                                                 "#661100", "#6699CC"};

// gnuplot strings in single quotes take everything literally except the quote itself, doubled.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

std::string number(double x) {
  if (!std::isfinite(x)) return "NaN";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream os(path);
  os << text;
  if (!os.flush()) throw PlotError(path.string() + ": cannot write: " + std::strerror(errno));
}

bool has_points(const PlotSeries& s) { return !s.x.empty() && !s.y.empty(); }

std::string style_of(const PlotSeries& s) {
  const std::string& color = s.colour;
  switch (s.style) {
    case PlotSeries::Style::Dashed:
      return "with lines lw 1.2 dt 2 lc rgb '" + color + "'";
    case PlotSeries::Style::Dotted:
      return "with lines lw 1.5 dt 3 lc rgb '" + color + "'";
    case PlotSeries::Style::DashDot:
      return "with lines lw 1.2 dt 4 lc rgb '" + color + "'";
    case PlotSeries::Style::Points:
      return "with points pt 7 ps 0.5 lc rgb '" + color + "'";
    case PlotSeries::Style::Triangles:
      return "with points pt 9 ps 0.8 lc rgb '" + color + "'";
    case PlotSeries::Style::Crosses:
      return "with points pt 2 ps 0.9 lc rgb '" + color + "'";
    case PlotSeries::Style::LinePoints:
      return "with linespoints lw 1.5 dt " + std::to_string(s.dash) + " pt " + std::to_string(6 + s.dash) +
             " ps 0.7 lc rgb '" + color + "'";
    case PlotSeries::Style::Line:
      break;
  }
  return "with lines lw 1.5 dt " + std::to_string(s.dash) + " lc rgb '" + color + "'";
}

}  // namespace

std::string plot_colour(int k) { return kPalette[static_cast<std::size_t>(k < 0 ? -k : k) % kPalette.size()]; }

void write_plot_files(const fs::path& dir, const PlotSpec& spec) {
  // The data: one block per series (gnuplot's "index"), blocks separated by two blank lines.
  std::ostringstream data;
  data << "# " << spec.title << "\n# x: " << spec.xlabel << "; y: " << spec.ylabel << '\n';
  std::vector<std::size_t> blocks;  // series index of each block
  bool zeros_on_floor = false;      // a value of exactly 0 drawn at log_floor
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const PlotSeries& s = spec.series[k];
    if (!has_points(s)) continue;
    if (!blocks.empty()) data << "\n\n";
    data << "# " << s.title << '\n';
    blocks.push_back(k);
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      const double x = spec.log_x && std::isfinite(s.x[i]) ? std::max(s.x[i], spec.log_floor) : s.x[i];
      const double y = spec.log_y && std::isfinite(s.y[i]) ? std::max(s.y[i], spec.log_floor) : s.y[i];
      zeros_on_floor = zeros_on_floor || (spec.log_y && s.y[i] == 0.0) || (spec.log_x && s.x[i] == 0.0);
      data << number(x) << ' ' << number(y) << '\n';
    }
  }
  write_text(dir / (spec.name + ".dat"), data.str());

  // The key's entries: the series it lists, the key's own entries and the horizontal line.
  std::size_t entries = spec.key.size() + (spec.hline ? 1 : 0);
  for (std::size_t b : blocks) entries += spec.series[b].in_key ? 1 : 0;
  const std::size_t rows = (entries + kKeyColumns - 1) / kKeyColumns;
  std::ostringstream gp;
  gp << "# " << spec.title << ": rerun with `gnuplot " << spec.name << ".gp` in this directory.\n"
     << "set terminal svg size " << kPlotWidth << ',' << kPlotHeight + kKeyRowHeight * static_cast<int>(rows)
     << " dynamic enhanced font 'Helvetica,13' background '#ffffff'\n"
     << "set output " << quoted(spec.name + ".svg") << '\n'
     << "set title " << quoted(spec.title) << " noenhanced\n"
     << "set xlabel " << quoted(spec.xlabel) << " noenhanced\n"
     << "set ylabel " << quoted(spec.ylabel) << " noenhanced\n"
     << "set grid lc rgb '#dddddd'\n"
     << "set key outside below center horizontal maxcols " << kKeyColumns << " noenhanced\n"
     << "set datafile missing 'NaN'\n";
  if (spec.log_x) gp << "set logscale x\nset format x '10^{%L}'\n";
  if (spec.log_y) gp << "set logscale y\nset format y '10^{%L}'\n";
  if (zeros_on_floor) {
    gp << "set label 2 " << quoted("values of exactly 0 are drawn at " + number(spec.log_floor))
       << " at graph 0.01, graph 0.03 left font ',10' tc rgb '#555555' noenhanced\n";
  }
  std::vector<std::string> parts;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const PlotSeries& s = spec.series[blocks[b]];
    parts.push_back(quoted(spec.name + ".dat") + " index " + std::to_string(b) + " using 1:2 " + style_of(s) +
                    (s.in_key ? " title " + quoted(s.title) : std::string(" notitle")));
  }
  if (!parts.empty()) {
    for (const PlotSeries& k : spec.key) parts.push_back("NaN " + style_of(k) + " title " + quoted(k.title));
  }
  if (spec.hline) {
    parts.push_back(number(*spec.hline) + " with lines lw 1 dt 3 lc rgb '#777777' title " + quoted(spec.hline_title));
  }
  if (parts.empty()) {
    // Nothing to draw: an empty frame says so rather than a gnuplot error.
    gp << "set label 1 'no data' at graph 0.5, graph 0.5 center\nset xrange [0:1]\nset yrange [0:1]\n"
       << "plot NaN notitle\n";
  } else {
    gp << "plot ";
    for (std::size_t i = 0; i < parts.size(); ++i) gp << (i == 0 ? "" : ", \\\n     ") << parts[i];
    gp << '\n';
  }
  write_text(dir / (spec.name + ".gp"), gp.str());
}

void render_plot(const fs::path& dir, const std::string& name) {
  const fs::path log = dir / (name + ".log");
  const std::string script = name + ".gp";
  const pid_t pid = fork();
  if (pid < 0) throw PlotError(std::string("cannot start gnuplot: ") + std::strerror(errno));
  if (pid == 0) {
    // The child: gnuplot in the plot's directory, its messages into the log.
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    if (chdir(dir.c_str()) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw PlotError(std::string("waiting for gnuplot: ") + std::strerror(errno));
  }
  std::string messages;
  {
    std::ifstream in(log);
    std::ostringstream all;
    all << in.rdbuf();
    messages = all.str();
  }
  std::error_code ignored;
  fs::remove(log, ignored);
  const fs::path svg = dir / (name + ".svg");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(svg)) {
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::string why = code == 127 ? "gnuplot not found (scripts/install-deps installs gnuplot-nox)"
                                  : "gnuplot failed (exit " + std::to_string(code) + ")";
    if (!messages.empty()) why += ": " + messages;
    throw PlotError(name + ".svg: " + why);
  }
}

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream dirs(path);
  std::string d;
  while (std::getline(dirs, d, ':')) {
    const fs::path candidate = (d.empty() ? fs::current_path() : fs::path(d)) / "gnuplot";
    if (access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::vector<std::string> write_plots(const std::filesystem::path& dir, const std::vector<PlotSpec>& plots,
                                     std::vector<std::string>& notes) {
  std::vector<std::string> rendered;
  const bool gnuplot = gnuplot_available();
  if (!gnuplot && !plots.empty()) {
    notes.push_back("gnuplot not found (scripts/install-deps installs gnuplot-nox): plots not rendered; "
                    "their data and scripts are written");
  }
  for (const PlotSpec& spec : plots) {
    write_plot_files(dir, spec);
    if (!gnuplot) continue;
    try {
      render_plot(dir, spec.name);
      rendered.push_back(spec.name);
    } catch (const PlotError& e) {
      notes.push_back(e.what());
    }
  }
  return rendered;
}

}  // namespace boxpile
