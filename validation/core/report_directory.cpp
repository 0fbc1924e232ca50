#include "boxpile/validation/core/report_directory.hpp"

#include <fcntl.h>
#include <stdio.h>  // renameat2 (glibc 2.28)
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace boxpile {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse_report(const fs::path& target, const std::string& why) {
  throw ReportDirectoryError(target, why);
}

void check_target(const fs::path& target, const std::vector<fs::path>& inputs,
                  const std::string& marker) {
  try {
    check_output_path(target, OutputKind::Directory, inputs);
  } catch (const OutputError& e) {
    refuse_report(target, e.why());
  }
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(target, ec))) return;
  const bool empty = fs::is_empty(target, ec);
  if (ec) refuse_report(target, ec.message());
  if (!empty && !fs::exists(target / marker)) {
    refuse_report(target, "exists and holds no " + marker + ": not a boxpile report, so it is left alone; "
                   "choose another directory");
  }
}

}  // namespace

ReportDirectory::ReportDirectory(fs::path target, const std::vector<fs::path>& inputs, std::string marker)
    : target_(std::move(target)), marker_(std::move(marker)) {
  if (target_.empty()) refuse_report(target_, "no directory given");
  // "out/" names the directory "out": drop the trailing separator, so that its parent is found.
  if (!target_.has_filename()) target_ = target_.parent_path();
  if (target_.empty()) target_ = ".";
  check_target(target_, inputs, marker_);
  std::error_code ec;
  in_place_ = fs::is_directory(fs::symlink_status(target_, ec)) && fs::is_empty(target_, ec);
  fs::path parent = target_;
  if (!in_place_) {
    try {
      parent_.emplace(target_);
      parent = parent_->path();
    } catch (const OutputError& e) {
      refuse_report(target, e.why());
    }
  }
  try {
    Staging staging = create_staging(in_place_ ? target_ / "report" : target_, parent, OutputKind::Directory);
    staging_ = std::move(staging.path);
    registration_ = std::move(staging.registration);
  } catch (const OutputError& e) {
    refuse_report(target_, e.why());
  }
  // mkdtemp makes it private (0700); the report gets the permissions of any new directory.
  const mode_t mask = umask(0);
  umask(mask);
  chmod(staging_.c_str(), 0777 & ~mask);
}

ReportDirectory::~ReportDirectory() {
  if (committed_ || staging_.empty()) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void ReportDirectory::commit() {
  std::error_code ec;
  if (in_place_) {
    // The target held nothing but the staging: its files move out of it, signals waiting.
    for (const fs::directory_entry& e : fs::directory_iterator(target_, ec)) {
      if (e.path() != staging_) refuse_report(target_, "something was written into it during the run: " + e.path().string());
    }
    const HeldSignals held;
    for (const fs::directory_entry& e : fs::directory_iterator(staging_)) {
      fs::rename(e.path(), target_ / e.path().filename(), ec);
      if (ec) refuse_report(target_, "cannot move the finished report into place: " + ec.message());
    }
    committed_ = true;
    fs::remove(staging_, ec);
    return;
  }
  check_target(target_, {}, marker_);  // it may have changed during the run
  if (!fs::exists(target_, ec)) {
    fs::rename(staging_, target_, ec);
    if (ec) refuse_report(target_, "cannot rename the finished report into place: " + ec.message());
    committed_ = true;
    if (parent_) parent_->keep();
    return;
  }
  // Swap the two directories in one step, then delete the old report (now at the staging path).
  if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
    committed_ = true;
    fs::remove_all(staging_, ec);
    return;
  }
  // No exchange on this file system: move the old report aside, the new one in, the old one out;
  // signals wait (a signal between the renames would delete the new report and leave the old
  // one aside, unregistered).
  const HeldSignals held;
  const fs::path old = staging_.string() + "-old";
  fs::rename(target_, old, ec);
  if (ec) refuse_report(target_, "cannot replace the previous report: " + ec.message());
  fs::rename(staging_, target_, ec);
  if (ec) {
    std::error_code ignored;
    fs::rename(old, target_, ignored);  // put the previous report back
    refuse_report(target_, "cannot rename the finished report into place: " + ec.message());
  }
  committed_ = true;
  fs::remove_all(old, ec);
}

void write_report_file(const fs::path& file, std::string_view text) {
  std::ofstream os(file);
  os << text;
  if (!os.flush()) throw std::runtime_error(file.string() + ": write failed");
}

}  // namespace boxpile
