#include "boxpile/validation/core/data_directory.hpp"

#include <cstdlib>

namespace boxpile {
namespace {

namespace fs = std::filesystem;

// Set by the build: the data folder relative to the program's folder, e.g. "../share/boxpile".
// The build tree mirrors the install tree, so one path serves both.
constexpr const char* kDataFromProgram = BOXPILE_DATA_FROM_PROGRAM;
// Present in every data folder.
constexpr const char* kDataMarker = "fixtures";

fs::path program_directory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the boxpile program's own path: " + ec.message());
  return exe.parent_path();
}

}  // namespace

fs::path data_directory() {
  const fs::path dir = (program_directory() / kDataFromProgram).lexically_normal();
  if (fs::exists(dir / kDataMarker)) return dir;
  throw std::runtime_error("boxpile's data folder (fixtures, report assets) is missing: looked in " + dir.string() +
                           " (install boxpile with `cmake --install`, or run it from its build tree)");
}

fs::path data_path(const std::string& relative) { return data_directory() / relative; }

}  // namespace boxpile
