#include <filesystem>
#include <iostream>
#include <vector>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/core/recording.hpp"
#include "boxpile/validation/replay/replay_data.hpp"
#include "boxpile/validation/replay/replay_page.hpp"
#include "boxpile/validation/compare/report.hpp"

namespace boxpile::cli {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& path, std::size_t max_bytes) {
  return json_input::parse(json_input::read_text_file(path.string(), max_bytes), path.string());
}

// A report directory's page data (replay.json), with the marks renewed from its report.json.
nlohmann::json report_replay(const fs::path& dir, std::size_t max_bytes) {
  const fs::path report = dir / kReportJson, data = dir / kReplayData;
  if (!fs::is_regular_file(report) || !fs::is_regular_file(data)) {
    throw InputError(dir.string(), "", std::string("not a boxpile report directory: it needs report.json and ") +
                                           kReplayData + " (written by boxpile compare)");
  }
  nlohmann::json replay = read_json(data, max_bytes);
  check_replay_data(replay, data.string());
  nlohmann::json marks = nlohmann::json::array();
  for (const ReplayMark& m : marks_from_report(read_json(report, max_bytes))) marks.push_back({{"t", m.t}, {"label", m.label}});
  replay["marks"] = std::move(marks);
  return replay;
}

// The page's data for one run file (`boxpile run --out`).
nlohmann::json run_replay(const fs::path& file, std::size_t max_bytes) {
  const Recording recording = recording_from_json(read_json(file, max_bytes), file.string());
  return replay_data(recording.scene + " (" + recording.engine + ")", {&recording}, {});
}

// The files a page is made from: an output may be none of them.
std::vector<fs::path> view_inputs(const fs::path& input, bool directory) {
  if (!directory) return {input};
  return {input / kReportJson, input / kReplayData};
}

}  // namespace

void add_view_command(CLI::App& app, ViewOptions& options) {
  CLI::App* cmd = app.add_subcommand("view", "Write a replay page (HTML, opens offline in a browser) for a run file "
                                             "(boxpile run --out) or a report directory (boxpile compare)");
  cmd->add_option("input", options.input, "A run file (JSON) or a report directory")->required();
  cmd->add_option("--out", options.out,
                  "The page to write (default: replay.html in a report directory, RUN.html beside a run file)");
  add_input_limit_option(*cmd, options.max_input_bytes);
}

int run_view(const ViewOptions& options) {
  const fs::path input(options.input);
  if (!fs::exists(input)) throw InputError(options.input, "", "no such file or directory");
  const bool directory = fs::is_directory(input);
  fs::path out = options.out.empty() ? (directory ? input / kReplayPage : fs::path(input).replace_extension(".html"))
                                     : fs::path(options.out);
  if (!directory && fs::absolute(out).lexically_normal() == fs::absolute(input).lexically_normal()) {
    throw InputError(out.string(), "", "the page would replace its own input");
  }
  OutputFile page(out, view_inputs(input, directory));  // checked and staged before any work
  const nlohmann::json data = directory ? report_replay(input, options.max_input_bytes) : run_replay(input, options.max_input_bytes);
  write_replay_page(data, load_three_js(), page);
  std::cout << "replay: " << fs::absolute(out).lexically_normal().string() << '\n';
  return kExitOk;
}

}  // namespace boxpile::cli
