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

RunMonitor::RunMonitor(const Scene& scene)
    : scene_(scene), checks_(read_scene_checks(scene)), bodies_(make_bodies(scene)) {
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
    if (!scene_.bodies[i].fixed) m_.max_spin = std::max(m_.max_spin, states[i].angular_velocity.norm());
  }

  // Each check the scene holds, then the figures of its own that the measures carry.
  for (const SceneCheckSet::Held& h : checks_.held) h.check->observe(view(), step, t, states);
  for (const SceneCheckSet::Held& h : checks_.held) h.check->record(m_);
}

std::vector<SceneCheckResult> RunMonitor::evaluate() const {
  std::vector<SceneCheckResult> out;
  out.push_back({"finite", m_.finite ? 1.0 : 0.0, 1.0, true, m_.finite, "", "finite", ""});
  if (!m_.finite) return out;  // nothing else means anything once a state is NaN
  for (const SceneCheckSet::Held& h : checks_.held) {
    const std::size_t first = out.size();
    h.check->evaluate(view(), out);
    const auto reason = checks_.reasons.find(std::string(h.row->key));
    for (std::size_t i = first; i < out.size(); ++i) {
      out[i].key = h.row->key;
      if (reason != checks_.reasons.end()) out[i].reason = reason->second;
    }
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
