// The one error type for bad input files: it names the file, the JSON path and what is wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace boxpile {

class InputError : public std::runtime_error {
 public:
  // file: the path given by the user; json_path: e.g. "bodies[3].half_extents[1]" (empty for the
  // whole document); what: what is wrong, e.g. "must be > 0, got -1".
  InputError(std::string file, std::string json_path, std::string what)
      : std::runtime_error(format(file, json_path, what)),
        file_(std::move(file)), json_path_(std::move(json_path)) {}

  const std::string& file() const { return file_; }
  const std::string& json_path() const { return json_path_; }

 private:
  static std::string format(const std::string& file, const std::string& path,
                            const std::string& what) {
    return file + ": " + (path.empty() ? std::string() : path + ": ") + what;
  }
  std::string file_;
  std::string json_path_;
};

}  // namespace boxpile
