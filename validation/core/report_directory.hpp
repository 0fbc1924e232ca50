// A report directory that is either complete or absent: files are written into a staging
// directory beside it, which replaces the report directory in one rename at the end. A failure
// before that (or an exception, an interruption, an abort) removes the staging directory and
// leaves any previous report as it was. The checks and the clean-up are those of every output
// (validation/core/output_safety.hpp).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/validation/core/output_safety.hpp"

namespace boxpile {

// The report directory cannot be used: it cannot be created or written, or it is not a
// directory, or a directory that holds something other than a boxpile report. Bad input: the CLI
// exits with 2.
class ReportDirectoryError : public OutputError {
 public:
  ReportDirectoryError(const std::filesystem::path& target, const std::string& why)
      : OutputError("report directory", target, why) {}
};

class ReportDirectory {
 public:
  // Checks `target` (check_output_path: no links, devices, FIFOs, sockets, nothing that holds one
  // of `inputs`) and creates the staging directory (and any missing parents of `target`). An
  // existing `target` is accepted only if it is empty or holds `marker`, the one file that marks
  // a boxpile report (it will be replaced); anything else is refused rather than deleted.
  explicit ReportDirectory(std::filesystem::path target, const std::vector<std::filesystem::path>& inputs = {},
                           std::string marker = "report.json");
  ~ReportDirectory();
  ReportDirectory(const ReportDirectory&) = delete;
  ReportDirectory& operator=(const ReportDirectory&) = delete;

  // Where to write the report's files until commit().
  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& target() const { return target_; }

  // Puts the staged report in place of the target, atomically where the file system can swap
  // two directories (renameat2 RENAME_EXCHANGE), else by two renames.
  void commit();

 private:
  std::filesystem::path target_;
  std::optional<PreparedParent> parent_;  // absent when the report fills an existing empty directory
  std::filesystem::path staging_;
  std::unique_ptr<StagedPath> registration_;
  std::string marker_;
  // An existing empty directory (`--report .` in an empty folder) is filled in place: its staging
  // lies inside it and commit() moves the files out of it, so that the directory (perhaps the
  // shell's working directory) stays the same one, and its parent need not be writable.
  bool in_place_ = false;
  bool committed_ = false;
};

// Writes one file of a report into its staging directory (ReportDirectory::staging()); the whole
// directory is renamed into place by commit(). Throws std::runtime_error naming the file.
void write_report_file(const std::filesystem::path& file, std::string_view text);

}  // namespace boxpile
