// Where boxpile's data lives: the fixtures (and report assets) under P/share/boxpile beside an
// installed program, or build/share/boxpile in a build tree (links into the source tree). Found
// from the running program's own path, never from a path fixed at compile time, so an installed
// or moved boxpile works from any directory.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace boxpile {

// The data folder; std::runtime_error naming the places looked at when there is none.
std::filesystem::path data_directory();

// A file or folder under the data folder, e.g. data_path("fixtures/contacts").
std::filesystem::path data_path(const std::string& relative);

}  // namespace boxpile
