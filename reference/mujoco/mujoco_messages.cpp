#include "boxpile/reference/mujoco/mujoco_messages.hpp"

#include <mutex>

#include <mujoco/mujoco.h>

namespace boxpile {
namespace {

std::mutex log_mutex;
MujocoMessageLog log;

void count_warning(const char* msg) {
  const std::lock_guard<std::mutex> lock(log_mutex);
  ++log.count;
  log.last = msg ? msg : "";
}

// MuJoCo calls the error handler and, should it return, carries on from an undefined state;
// throwing unwinds out of the library instead (it is built with unwind tables, as ODE is).
[[noreturn]] void throw_error(const char* msg) {
  throw MujocoError(std::string("mujoco: ") + (msg ? msg : "unknown error"));
}

}  // namespace

MujocoMessageLog mujoco_messages() {
  const std::lock_guard<std::mutex> lock(log_mutex);
  return log;
}

namespace reference_detail {

void ensure_mujoco_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = &throw_error;
    mju_user_warning = &count_warning;
  });
}

}  // namespace reference_detail
}  // namespace boxpile
