// A report directory that is either complete or absent: files are written into a staging
// directory beside it, which replaces the report directory in one rename at the end. A failure
// before that (or an exception) removes the staging directory and leaves any previous report as
// it was.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace boxpile {

// The report directory cannot be used: it cannot be created or written, or it is a file, or a
// directory that holds something other than a boxpile report. Bad input: the CLI exits with 2.
class ReportDirectoryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ReportDirectory {
 public:
  // Checks `target` and creates the staging directory (and any missing parents of `target`).
  // An existing `target` is accepted only if it is empty or holds `marker`, the one file that
  // marks a boxpile report (it will be replaced); anything else is refused rather than deleted.
  explicit ReportDirectory(std::filesystem::path target, std::string marker = "report.json");
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
  std::filesystem::path staging_;
  std::string marker_;
  bool committed_ = false;
};

}  // namespace boxpile
