// Helpers of the tests that write files or drive the boxpile executable: scratch directories under
// the build tree, whole-file reads, fixtures by name, and the exit code of a boxpile command.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "boxpile/sim/io/scene_loader.hpp"

namespace boxpile::test {

inline Scene fixture(const std::string& name) {
  return load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + name + ".json");
}

// A fresh directory under the build tree for one test.
inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(BOXPILE_TEST_WORK) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

inline void write(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

// Runs the boxpile executable; returns its exit code.
inline int run_boxpile(const std::string& args) {
  const std::string command = std::string(BOXPILE_EXE) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace boxpile::test
