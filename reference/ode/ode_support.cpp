#include "boxpile/reference/ode/ode_support.hpp"

#include <cstdarg>
#include <cstdio>
#include <mutex>

#include "boxpile/reference/convention.hpp"
#include "boxpile/reference/ode/ode_engine.hpp"

namespace boxpile {
namespace {

// ODE reports through a C callback with no user data, so the count is process-wide.
std::mutex g_message_mutex;
OdeMessageLog g_messages;

std::string format_ode_text(const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  return text;
}

void count_ode_message(int errnum, const char* msg, va_list ap) {
  const std::string text = format_ode_text(msg, ap);
  const std::lock_guard<std::mutex> lock(g_message_mutex);
  ++g_messages.count;
  g_messages.last = "ODE message " + std::to_string(errnum) + ": " + text;
}

// ODE calls abort() (or exit()) once an error or debug handler returns, so these never return:
// the exception unwinds through ODE (built as C++ with exception tables) back to our caller.
[[noreturn]] void throw_ode_error(int errnum, const char* msg, va_list ap) {
  throw OdeError("ODE error " + std::to_string(errnum) + ": " + format_ode_text(msg, ap));
}

[[noreturn]] void throw_ode_internal_error(int errnum, const char* msg, va_list ap) {
  throw OdeError("ODE internal assertion " + std::to_string(errnum) + ": " + format_ode_text(msg, ap));
}

}  // namespace

OdeMessageLog ode_messages() {
  const std::lock_guard<std::mutex> lock(g_message_mutex);
  return g_messages;
}

namespace reference_detail {

void ensure_ode_initialised() {
  static std::once_flag once;
  std::call_once(once, [] {
    dInitODE2(0);
    // Messages (such as dWorldStep's "LCP internal error, s <= 0"): ODE carries on after them,
    // so they are counted. Errors and internal assertions would abort the process once the
    // handler returns, so those handlers throw OdeError instead.
    dSetMessageHandler(count_ode_message);
    dSetErrorHandler(throw_ode_error);
    dSetDebugHandler(throw_ode_internal_error);
  });
}

OrientedBox box_of_geom(dGeomID geom) {
  dVector3 lengths;
  dGeomBoxGetLengths(geom, lengths);
  return {from_ode(dGeomGetPosition(geom)), matrix_from_ode(dGeomGetRotation(geom)),
          0.5 * from_ode(lengths)};
}

Contact ode_box_box_contact(const OrientedBox& a, const OrientedBox& b, const dContactGeom& g) {
  const Vec3 n = from_ode(g.normal);
  const Vec3 p = from_ode(g.pos);
  const FeatureKind kind = box_box_kind(a, b, n);
  const Vec3 position = kind == FeatureKind::EdgeEdge ? p : ode_face_midpoint(a, b, p, n, g.depth);
  return {position, n, g.depth, kind_only(kind)};
}

Contact ode_box_plane_contact(const dContactGeom& g) {
  const Vec3 n = from_ode(g.normal);
  return {from_ode(g.pos) + 0.5 * g.depth * n, n, g.depth, kind_only(FeatureKind::Plane)};
}

}  // namespace reference_detail
}  // namespace boxpile
