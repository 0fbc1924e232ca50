#include "boxpile/validation/stability/stability_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace boxpile {
namespace {

// A start energy smaller than this (J) has no meaningful fraction: the energy checks then compare
// the absolute change with the tolerance itself (as if |E0| were 1 J).
constexpr double kSmallestEnergyScale = 1e-12;

double kinetic_energy(const RigidBody& b) {
  if (b.fixed) return 0.0;
  return 0.5 * b.mass * b.v.squaredNorm() + 0.5 * b.omega.dot(b.R * b.inertia_body * b.R.transpose() * b.omega);
}

SceneCheckResult at_most(std::string name, double value, double limit, std::string unit) {
  return {std::move(name), value, limit, false, value <= limit, std::move(unit), {}, {}};
}

// The radius of a sphere about the body's centre of mass that holds all its boxes.
double enclosing_radius(const RigidBody& b) {
  double r = 0.0;
  for (const BoxShape& box : b.shapes) r = std::max(r, box.offset.norm() + box.half_extents.norm());
  return r;
}

}  // namespace

double smallest_edge(const Scene& scene) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const BodyDesc& b : scene.bodies)
    for (const BoxShape& box : b.boxes) smallest = std::min(smallest, 2.0 * box.half_extents.minCoeff());
  return std::isfinite(smallest) ? smallest : 0.0;
}

RunMonitor::RunMonitor(const Scene& scene) : scene_(scene), bodies_(make_bodies(scene)) {
  up_ = -down_direction(scene.gravity);
  m_.smallest_edge = smallest_edge(scene);
  for (const RigidBody& b : bodies_) radii_.push_back(enclosing_radius(b));
}

void RunMonitor::observe(long step, const std::vector<BodyState>& states) {
  if (!m_.finite) return;
  set_body_states(bodies_, states);
  const Vec3 g = scene_.effects.gravity ? scene_.gravity : Vec3::Zero();
  const Energy e = measure_energy(bodies_, g);
  energy_now_ = e.total();
  kinetic_now_ = e.kinetic();
  const double t = static_cast<double>(step) * scene_.time.dt;
  if (step == 0) {
    const double edge = m_.smallest_edge;
    m_ = RunMeasures{};
    m_.smallest_edge = edge;
    m_.energy_start = energy_now_;
    start_.clear();
    for (const BodyState& s : states) start_.push_back(s.position);
    rebound_ = ReboundTracker{};
    side_margins_.assign(scene_.checks.stays_behind.size(), std::numeric_limits<double>::infinity());
  }
  m_.steps = step;

  // Energy against the start, as a fraction of |E0|.
  const double scale = std::max(std::abs(m_.energy_start), kSmallestEnergyScale);
  const double change = (energy_now_ - m_.energy_start) / scale;
  if (change > m_.energy_rise) {
    m_.energy_rise = change;
    m_.energy_rise_t = t;
  }
  m_.energy_change = std::max(m_.energy_change, std::abs(change));

  m_.deepest_penetration = std::max(m_.deepest_penetration, measure_penetration(bodies_, scene_.ground).depth);

  // Displacements and spin.
  const std::optional<TurningCheck>& turning = scene_.checks.no_turning;
  const bool spin_window = !turning || !turning->until || t <= *turning->until + 0.5 * scene_.time.dt;
  m_.kinetic_end = 0.0;
  m_.kinetic_end_max_body = 0.0;
  m_.speed_end_max = 0.0;
  m_.height_error = 0.0;
  m_.drift = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Vec3 d = states[i].position - start_[i];
    m_.largest_move = std::max(m_.largest_move, d.norm());
    const double height = d.dot(up_);
    m_.height_error = std::max(m_.height_error, std::abs(height));
    m_.drift = std::max(m_.drift, (d - height * up_).norm());
    const double k = kinetic_energy(bodies_[i]);
    m_.kinetic_end += k;
    m_.kinetic_end_max_body = std::max(m_.kinetic_end_max_body, k);
    if (!scene_.bodies[i].fixed)
      m_.speed_end_max = std::max(m_.speed_end_max, states[i].velocity.norm() + states[i].angular_velocity.norm() * radii_[i]);
    if (spin_window && !scene_.bodies[i].fixed) m_.max_spin = std::max(m_.max_spin, states[i].angular_velocity.norm());
  }
  if (scene_.checks.rest && !m_.moved_at_step && m_.largest_move > scene_.checks.rest->max_move) m_.moved_at_step = step;
  if (scene_.checks.rebound) observe_rebound(states);
  for (std::size_t k = 0; k < side_margins_.size(); ++k) {
    const SideCheck& c = scene_.checks.stays_behind[k];
    const double margin = c.normal.dot(states[static_cast<std::size_t>(c.body)].position) - c.offset;
    side_margins_[k] = std::min(side_margins_[k], margin);
  }
}

void RunMonitor::observe_rebound(const std::vector<BodyState>& states) {
  const ReboundCheck& c = *scene_.checks.rebound;
  const BodyState& s = states[static_cast<std::size_t>(c.body)];
  rebound_.observe(s.position.dot(up_) - c.rest_height, s.velocity.dot(up_));
  m_.rebound = rebound_.apex();
}

std::vector<SceneCheckResult> RunMonitor::evaluate() const {
  const SceneChecks& c = scene_.checks;
  std::vector<SceneCheckResult> out;
  out.push_back({"finite", m_.finite ? 1.0 : 0.0, 1.0, true, m_.finite, "", "finite", ""});
  if (!m_.finite) return out;  // nothing else means anything once a state is NaN
  // Each result below is tagged with its scene key once the list is complete.
  std::vector<std::string> keys = {"finite"};
  auto tag = [&](const char* key) { keys.resize(out.size(), key); };

  out.push_back(at_most("energy_rise", m_.energy_rise, c.energy_rise, ""));
  tag("energy_rise");
  if (c.energy_conserved) out.push_back(at_most("energy_conserved", m_.energy_change, *c.energy_conserved, ""));
  tag("energy_conserved");
  out.push_back(at_most("penetration", m_.deepest_penetration, c.penetration * m_.smallest_edge, "m"));
  tag("penetration");
  if (c.rest) {
    out.push_back(at_most("rest_speed", m_.speed_end_max, c.rest->speed, "m/s"));
    out.push_back(at_most("rest_move", m_.largest_move, c.rest->max_move, "m"));
  }
  tag("rest");
  if (c.no_turning) out.push_back(at_most("no_turning", m_.max_spin, c.no_turning->limit, "rad/s"));
  tag("no_turning");
  if (c.rebound) {
    // The relative error of the rebound height; no bounce at all counts as an error of 1.
    const double error = m_.rebound ? std::abs(*m_.rebound - c.rebound->height) / c.rebound->height : 1.0;
    out.push_back(at_most("rebound", error, c.rebound->tolerance, ""));
  }
  tag("rebound");
  for (const SlideCheck& s : c.slides) {
    const std::size_t i = static_cast<std::size_t>(s.body);
    const double moved = (bodies_[i].frame_pose().position - start_[i]).norm();
    out.push_back(at_most("slide " + scene_.bodies[i].name, std::abs(moved - s.distance), s.tolerance, "m"));
  }
  tag("slides");
  for (std::size_t k = 0; k < c.stays_behind.size(); ++k) {
    const SideCheck& s = c.stays_behind[k];
    const double margin = side_margins_[k];
    out.push_back({"stays_behind " + scene_.bodies[static_cast<std::size_t>(s.body)].name, margin, 0.0, true,
                   margin >= 0.0, "m", {}, {}});
  }
  tag("stays_behind");
  for (std::size_t i = 1; i < out.size(); ++i) {
    out[i].key = keys[i];
    if (const auto r = c.reasons.find(keys[i]); r != c.reasons.end()) out[i].reason = r->second;
  }
  return out;
}

const SceneCheckResult* first_instability(const std::vector<SceneCheckResult>& results) {
  for (const SceneCheckResult& r : results) {
    if (r.passed) continue;
    if (r.name == "finite" || r.name == "energy_rise" || r.name == "energy_conserved" || r.name == "rest_speed" ||
        r.name == "rest_move")
      return &r;
  }
  return nullptr;
}

std::string describe(const SceneCheckResult& r) {
  if (r.name == "finite") return r.passed ? "finite" : "NaN";
  auto fmt = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return std::string(buf);
  };
  const char* relation = r.at_least ? (r.passed ? ">=" : "<") : (r.passed ? "<=" : ">");
  return r.name + " " + fmt(r.value) + (r.unit.empty() ? "" : " " + r.unit) + " " + relation + " " + fmt(r.limit);
}

bool all_passed(const std::vector<SceneCheckResult>& results) {
  return std::all_of(results.begin(), results.end(), [](const SceneCheckResult& r) { return r.passed; });
}

const SceneCheckResult* deciding_check(const std::vector<SceneCheckResult>& results) {
  const SceneCheckResult* closest = nullptr;
  double closest_ratio = -std::numeric_limits<double>::infinity();
  for (const SceneCheckResult& r : results) {
    if (!r.passed) return &r;
    // How much of its limit a passing check used (at-least checks: how close to the limit).
    const double ratio = r.at_least ? -r.value : (r.limit > 0.0 ? r.value / r.limit : 0.0);
    if (r.name != "finite" && ratio > closest_ratio) {
      closest_ratio = ratio;
      closest = &r;
    }
  }
  return closest;
}

}  // namespace boxpile
