#include "boxpile/validation/cli/report_command.hpp"

#include <filesystem>
#include <iostream>

namespace boxpile::cli {

CLI::Option* add_report_option(CLI::App& cmd, std::string& dir, std::string_view kind) {
  const std::string previous = kind.empty() ? "a previous report" : "a previous " + std::string(kind) + " report";
  return cmd
      .add_option("--out,--report", dir,
                  "Report directory (--out, as every command names its output; --report is the same), replaced as a whole when the report is complete (created if absent; an "
                  "existing one must be empty or hold " + previous + ")")
      ->capture_default_str();
}

void finish_report(ReportDirectory& dir, const std::vector<std::string>& notes, std::string_view summary,
                   std::string_view page) {
  dir.commit();
  for (const std::string& n : notes) std::cerr << "boxpile: warning: " << n << '\n';
  const std::filesystem::path path = std::filesystem::absolute(dir.target()) / page;
  std::cout << summary << "report: " << path.lexically_normal().string() << '\n';
}

}  // namespace boxpile::cli
