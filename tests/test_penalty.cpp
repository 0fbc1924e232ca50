// The penalty method against analytic predictions with stated tolerances: resting overlap,
// the bounce of a damped spring, static and dynamic friction on an incline, energy in a resting
// stack and the anchors' persistence (its allocation-free step: test_allocations.cpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/metrics.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/sim/solver/penalty_parameters.hpp"
#include "boxpile/sim/solver/impulse_method.hpp"
#include "boxpile/sim/solver/penalty_method.hpp"
#include "boxpile/sim/world.hpp"

using namespace boxpile;

namespace {

constexpr double kG = 9.81;

Scene fixture(const std::string& name) {
  return load_scene(std::string(BOXPILE_FIXTURES_DIR) + "/scenes/" + name + ".json");
}

Scene penalty(Scene s) {
  s.solver.method = "penalty";
  return s;
}

int steps_for(const Scene& s, double seconds) { return static_cast<int>(step_count(s.time.dt, seconds)); }

void run(World& w, double seconds) {
  for (int k = 0; k < steps_for(w.scene(), seconds); ++k) w.step();
}

// Kinetic and gravitational energy plus the springs' elastic energy, sum of k d^2 / 2 over the
// touching points of the last contact set.
double total_energy(const World& w, double stiffness) {
  double elastic = 0.0;
  std::vector<BodyContact> contacts;
  w.contacts(contacts);
  for (const BodyContact& c : contacts)
    if (c.contact.depth > 0.0) elastic += 0.5 * stiffness * c.contact.depth * c.contact.depth;
  return measure_energy(w.bodies(), w.scene().gravity).total() + elastic;
}

// The restitution of a mass on a linear spring-damper (ratio zeta) that lands at v0 and leaves
// when the force k d + c d' reaches 0 (the clamp: it never pulls), before d returns to 0:
// d(t) = v0 / wd e^(-zeta w t) sin(wd t), found by bisection on the force's sign change.
double clamped_restitution(double zeta) {
  const double omega = 1.0, wd = omega * std::sqrt(1.0 - zeta * zeta);
  auto depth = [&](double t) { return std::exp(-zeta * omega * t) * std::sin(wd * t) / wd; };
  auto rate = [&](double t) {
    return std::exp(-zeta * omega * t) * (std::cos(wd * t) - zeta * omega / wd * std::sin(wd * t));
  };
  auto force = [&](double t) { return omega * omega * depth(t) + 2.0 * zeta * omega * rate(t); };
  double lo = 0.5 * M_PI / wd, hi = M_PI / wd;  // the force changes sign once in between
  for (int i = 0; i < 60; ++i) (force(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return -rate(lo);
}

// A unit box (m = 1 kg) landing flat at 1 m/s on k = 1e4 N/m per corner, without gravity; the
// restitution it leaves with.
double landing_restitution(Scene s) {
  const double v0 = 1.0;
  s.effects.gravity = false;
  s.solver.penalty.stiffness = 1e4;
  s.solver.penalty.substeps = 40;  // h = dt / 40 = 1e-4 s, omega h = 0.02
  s.bodies[0].velocity = Vec3(0, 0, -v0);
  s.bodies[0].frame.position.z() += 0.01;
  World w(s);
  run(w, 0.2);
  return w.bodies()[0].v.z() / v0;
}

}  // namespace

TEST_CASE("a box at rest sinks m g / (4 k) on its four corners", "[penalty]") {
  const Scene s = penalty(fixture("box_at_rest"));
  const PenaltyParameters p = derive_penalty_parameters(s);
  World w(s);
  const double z0 = w.bodies()[0].x.z();
  run(w, 2.0);
  const double sink = z0 - w.bodies()[0].x.z();
  const double expected = s.bodies[0].mass * kG / (4.0 * p.stiffness);
  INFO("sank " << sink << " m, expected " << expected << " m (k = " << p.stiffness << " N/m)");
  CHECK(std::abs(sink - expected) <= 0.05 * expected);
  // The four corners began together and never parted: one anchor each, kept by feature id.
  CHECK(w.method_as<PenaltyMethod>()->counters().anchors_created == 4);
}

TEST_CASE("a stack of five sinks the sum over its levels, level j carrying j boxes", "[penalty]") {
  const Scene s = penalty(fixture("stack_5"));
  const PenaltyParameters p = derive_penalty_parameters(s);
  World w(s);
  const std::size_t top = s.bodies.size() - 1;
  const double z0 = w.bodies()[top].x.z();
  run(w, 3.0);
  const double m = s.bodies[0].mass;
  double expected = 0.0;  // the contact under level j from the top carries j boxes on 4 corners
  for (int j = 1; j <= 5; ++j) expected += j * m * kG / (4.0 * p.stiffness);
  const double sink = z0 - w.bodies()[top].x.z();
  INFO("the top box sank " << sink << " m, expected " << expected << " m");
  CHECK(std::abs(sink - expected) <= 0.05 * expected);
}

TEST_CASE("a box landing flat bounces with the damped spring's restitution", "[penalty]") {
  // Four corner springs k and dampers c under a box landing flat: one oscillator of stiffness
  // 4k and damping 4c, omega = sqrt(4k / m), zeta = 4c / (2 sqrt(4k m)). A linear spring-damper
  // leaves at e = exp(-zeta pi / sqrt(1 - zeta^2)). Ours never pulls (f_n >= 0): contact ends when
  // 4k d + 4c d' reaches 0, with the box still in the ground and moving out at e_clamp v0 > e v0.
  // The measured restitution lies between the two, within 0.02 of e_clamp (the step's own error,
  // omega h = 0.02): the clamp explains the whole difference.
  const double k = 1e4, m = 1.0;
  for (const double zeta : {0.05, 0.1, 0.3}) {
    Scene s = penalty(fixture("box_at_rest"));
    s.solver.penalty.damping = point_damping(k, m / 4.0, zeta);
    const double e_measured = landing_restitution(s);
    const double e_clamp = clamped_restitution(zeta);
    const double e_linear = restitution_for_damping_ratio(zeta);
    INFO("zeta " << zeta << ": measured e = " << e_measured << ", linear " << e_linear << ", clamped " << e_clamp);
    CHECK(e_measured >= e_linear - 0.01);
    CHECK(e_measured <= e_clamp + 0.01);
    CHECK(std::abs(e_measured - e_clamp) <= 0.02);
  }
}

TEST_CASE("without a damping key, a pair's restitution sets its damping ratio", "[penalty]") {
  // Material restitution 0.5 with the restitution effect: zeta = -ln 0.5 / sqrt(pi^2 + ln^2 0.5)
  // = 0.215 for the box-ground pair, and the box leaves as the damped spring of that ratio does.
  Scene s = penalty(fixture("box_at_rest"));
  s.effects.restitution = true;
  s.material.restitution = 0.5;
  const double zeta = damping_ratio_for_restitution(0.5);
  const double e_measured = landing_restitution(s);
  INFO("zeta " << zeta << ": measured e = " << e_measured << ", clamped " << clamped_restitution(zeta));
  CHECK(e_measured >= 0.5 - 0.01);
  CHECK(std::abs(e_measured - clamped_restitution(zeta)) <= 0.02);
}

TEST_CASE("on an incline, static friction above tan(theta) holds the box even when dynamic is below", "[penalty][friction]") {
  Scene s = penalty(fixture("incline_stick"));  // 20 degrees: tan = 0.364
  s.material.friction = 0.2;                    // mu_d below tan(theta)
  s.material.static_friction = 0.5;             // mu_s above it
  World w(s);
  const Vec3 start = w.bodies()[0].x;
  run(w, 0.2);  // settle into the springs
  const Vec3 settled = w.bodies()[0].x;
  run(w, 2.0);
  const double creep = (w.bodies()[0].x - settled).norm();
  INFO("crept " << creep << " m in 2 s (first 0.2 s: " << (settled - start).norm() << " m)");
  CHECK(creep < 2e-3);
}

TEST_CASE("on an incline, static friction below tan(theta) slides at g (sin - mu_d cos)", "[penalty][friction]") {
  Scene s = penalty(fixture("incline_stick"));
  s.material.friction = 0.2;
  s.material.static_friction = 0.3;  // below tan(20 deg) = 0.364
  World w(s);
  const double theta = std::atan2(-s.ground->normal.x(), s.ground->normal.z());
  const Vec3 down_slope = Vec3(-s.ground->normal.z(), 0.0, s.ground->normal.x()).normalized() *
                          (s.ground->normal.x() < 0 ? 1.0 : -1.0);
  run(w, 0.5);
  const double v1 = w.bodies()[0].v.dot(down_slope);
  run(w, 1.5);
  const double v2 = w.bodies()[0].v.dot(down_slope);
  const double a = (v2 - v1) / 1.5;
  const double expected = kG * (std::sin(theta) - 0.2 * std::cos(theta));
  INFO("a = " << a << " m/s^2, expected " << expected);
  CHECK(std::abs(a - expected) <= 0.03 * expected);
}

namespace {

// A unit box (1 kg) placed at rest on an incline of `degrees`, touching it exactly, mu_s and mu_d
// as given (the incline_stick fixture turned to the angle).
Scene incline(double degrees, double mu_s, double mu_d) {
  Scene s = penalty(fixture("incline_stick"));
  const double t = degrees * M_PI / 180.0;
  s.ground->normal = Vec3(-std::sin(t), 0.0, std::cos(t));
  s.bodies[0].frame.position = 0.5 * s.ground->normal;
  s.bodies[0].frame.orientation = Quat(Eigen::AngleAxisd(-t, Vec3::UnitY()));
  s.material.static_friction = mu_s;
  s.material.friction = mu_d;
  return s;
}

Vec3 down_slope(const Scene& s) { return Vec3(s.ground->normal.z(), 0.0, -s.ground->normal.x()) * -1.0; }

}  // namespace

TEST_CASE("static friction holds a box placed at rest on a slope from its first contact on", "[penalty][friction]") {
  // 25 degrees (tan = 0.466), mu_s 0.6 above it, mu_d 0.3 below: the box must not slide (the
  // dynamic slide would be g (sin - mu_d cos) t^2 / 2 = 2.96 m in 2 s). It only settles into its
  // springs, within 0.5 s: its corners' normal and friction springs carry m g cos and m g sin
  // (m g / (4 k) = 1 mm in all with k_f = k), the box tilts by the downhill corners' larger load
  // (the centre 0.42 mm further), and the uphill corners, loaded with (cos - sin) m g / 4, slip until
  // the downhill ones carry the rest (0.28 mm more): 1.45 mm by that account, 1.48 mm measured,
  // bounded here by twice m g / (4 k). Then it stays.
  const Scene s = incline(25.0, 0.6, 0.3);
  const PenaltyParameters p = derive_penalty_parameters(s);
  World w(s);
  const Vec3 start = w.bodies()[0].x;
  run(w, 0.5);
  const Vec3 settled = w.bodies()[0].x;
  const auto slid_early = w.method_as<PenaltyMethod>()->counters().sliding_points;
  run(w, 1.5);
  const double moved = (w.bodies()[0].x - start).norm();
  const double creep = (w.bodies()[0].x - settled).norm();
  const double settle = s.bodies[0].mass * kG / (4.0 * p.stiffness);
  INFO("moved " << moved << " m in 2 s, the springs' settling " << settle << " m; crept " << creep
                << " m after 0.5 s; sliding point-steps " << slid_early << " then " << w.method_as<PenaltyMethod>()->counters().sliding_points);
  CHECK(moved < 2.0 * settle);
  CHECK(creep < 1e-5);
  CHECK(w.bodies()[0].v.norm() < 1e-6);
}

TEST_CASE("a box sliding to rest under the static cone sticks again", "[penalty][friction]") {
  // Launched at 1 m/s down a 25 degree slope with mu_d 0.55 > tan 25 = 0.466: it brakes at
  // a = g (mu_d cos - sin) = 0.744 m/s^2, stops after v0^2 / (2 a) = 0.672 m and 1.34 s, and then
  // stays (mu_s 0.6 holds it).
  Scene s = incline(25.0, 0.6, 0.55);
  const Vec3 down = down_slope(s);
  s.bodies[0].velocity = down;
  World w(s);
  const Vec3 start = w.bodies()[0].x;
  const double t = 25.0 * M_PI / 180.0;
  const double a = kG * (0.55 * std::cos(t) - std::sin(t));
  run(w, 2.0);
  const Vec3 stopped = w.bodies()[0].x;
  const double slid = (stopped - start).dot(down);
  run(w, 1.0);
  const double creep = (w.bodies()[0].x - stopped).norm();
  INFO("slid " << slid << " m (expected " << 1.0 / (2.0 * a) << "), then crept " << creep << " m in 1 s");
  CHECK(std::abs(slid - 1.0 / (2.0 * a)) <= 0.03 / (2.0 * a));
  CHECK(creep < 1e-5);
  CHECK(w.bodies()[0].v.norm() < 1e-4);
}

TEST_CASE("a damper past the explicit bound is integrated implicitly: a stack of 5 settles", "[penalty]") {
  // Damping 450 N s/m per point, stiffness 1e5 N/m, 10 substeps: c h / m = 1.5 for a point
  // between two boxes (m = 1/8 kg), past the explicit damper's bound 1, where it reversed the
  // point every substep (the bottom box rang at 1.35 cm/s for 4.5 s). It settles to the springs'
  // sink, level j from the top carrying j boxes on 4 corners: sum j m g / (4 k).
  Scene s = penalty(fixture("stack_5"));
  s.solver.penalty.damping = 450.0;
  s.solver.penalty.stiffness = 1e5;
  s.solver.penalty.substeps = 10;
  World w(s);
  const double z0 = w.bodies().back().x.z();
  run(w, 4.5);
  double fastest = 0.0;
  for (const RigidBody& b : w.bodies()) fastest = std::max(fastest, b.v.norm());
  double expected = 0.0;
  for (int j = 1; j <= 5; ++j) expected += j * kG / (4.0 * 1e5);
  const double sink = z0 - w.bodies().back().x.z();
  INFO("fastest " << fastest << " m/s after 4.5 s; top sank " << sink << " m, expected " << expected);
  CHECK(fastest < 1e-6);
  CHECK(std::abs(sink - expected) <= 0.05 * expected);
}

TEST_CASE("energy never rises in a damped resting stack", "[penalty]") {
  // One penalty step per scene step (dt = the derived h), so that the contact set a step reports
  // (found at its start) belongs to the state the step before left: E_k = kinetic + potential
  // of state k + the springs' k d^2 / 2 at the points found in state k.
  Scene s = penalty(fixture("stack_5"));
  const PenaltyParameters p = derive_penalty_parameters(s);
  s.time.dt /= p.substeps;
  s.solver.penalty.substeps = 1;
  World w(s);
  w.step();
  double previous = measure_energy(w.bodies(), s.gravity).total();
  double worst_rise = 0.0, first = 0.0;
  for (int k = 0; k < steps_for(s, 3.0); ++k) {
    const double bodies = measure_energy(w.bodies(), s.gravity).total();
    w.step();
    const double e = bodies + total_energy(w, p.stiffness) - measure_energy(w.bodies(), s.gravity).total();
    if (k == 0) first = e;
    if (k > 0) worst_rise = std::max(worst_rise, e - previous);
    previous = e;
  }
  INFO("largest rise in one step: " << worst_rise << " J; energy " << first << " -> " << previous << " J");
  CHECK(worst_rise <= 1e-9);
  CHECK(previous < first);
}

TEST_CASE("the hard catalogue stands under the penalty method", "[penalty]") {
  // Each stays up: no box ends lower than its start by more than the derived springs' sink
  // (at most the 1 mm allowed overlap times the levels, 10 for the tallest) plus 1 mm, nor moves
  // sideways by more than `drift` (measured: 0 in the stacks, 1e-4 m in the pyramid).
  struct Case {
    const char* name;
    double drift;  // m
  };
  for (const Case c : {Case{"stack_10", 1e-3}, Case{"heavy_on_light", 1e-3}, Case{"pyramid", 1e-3}}) {
    DYNAMIC_SECTION(c.name) {
      const Scene s = penalty(fixture(c.name));
      World w(s);
      run(w, 5.0);
      double drop = 0.0, drift = 0.0;
      for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        const Vec3 now = w.bodies()[i].frame_pose().position;
        drop = std::max(drop, s.bodies[i].frame.position.z() - now.z());
        drift = std::max(drift, (now.head<2>() - s.bodies[i].frame.position.head<2>()).norm());
      }
      INFO("largest drop " << drop << " m, largest drift " << drift << " m");
      CHECK(drop <= 10 * kDefaultRestingOverlap + 1e-3);
      CHECK(drift <= c.drift);
    }
  }
}

TEST_CASE("the scene's method is the one that runs", "[penalty]") {
  World impulse(fixture("box_at_rest"));
  World pen(penalty(fixture("box_at_rest")));
  run(impulse, 0.1);
  run(pen, 0.1);
  CHECK(impulse.method_as<ImpulseMethod>()->counters().contact_loop_runs > 0);
  CHECK(impulse.method_as<PenaltyMethod>() == nullptr);
  CHECK(pen.method_as<ImpulseMethod>() == nullptr);
  CHECK(pen.method_as<PenaltyMethod>()->counters().substeps ==
        static_cast<std::uint64_t>(steps_for(pen.scene(), 0.1) * derive_penalty_parameters(pen.scene()).substeps));
}

TEST_CASE("derived penalty parameters follow their formulas", "[penalty]") {
  const Scene s = penalty(fixture("stack_10"));
  const PenaltyParameters p = derive_penalty_parameters(s);
  // Ten 1 kg cubes: the bottom carries 10 kg on four corners with a 1 mm overlap.
  CHECK_THAT(p.stack_mass, Catch::Matchers::WithinRel(10.0, 1e-12));
  CHECK_THAT(p.stiffness, Catch::Matchers::WithinRel(10.0 * kG / (4.0 * kDefaultRestingOverlap), 1e-12));
  CHECK_THAT(p.omega, Catch::Matchers::WithinRel(std::sqrt(p.stiffness / 0.25), 1e-12));
  CHECK_THAT(p.stable_step, Catch::Matchers::WithinRel(2.0 * (std::sqrt(2.0) - 1.0) / p.omega, 1e-12));
  CHECK(s.time.dt / p.substeps <= kStabilityFraction * p.stable_step);
  CHECK(s.time.dt / (p.substeps - 1) > kStabilityFraction * p.stable_step);
  CHECK_THAT(restitution_for_damping_ratio(damping_ratio_for_restitution(0.5)), Catch::Matchers::WithinRel(0.5, 1e-12));
}

// The stiffness is per contact point (docs/penalty.md, "Stiffness per point, not per area"): a
// cube turned 45 degrees on another rests on the octagon's 8 clipped points and sinks half as
// deep as an aligned one on 4, although its contact area is 0.83 of the aligned one's; reduced to
// four points it sinks as the aligned one. At rest the springs alone carry the weight, so the
// sink is m g / (n k) to rounding once the damper has settled the ringing.
TEST_CASE("the sink between two cubes is m g / (n k) for the n points of their contact", "[penalty]") {
  const double k = 1e4;
  const auto sink_between = [&](double yaw, bool reduce) {
    Scene s = penalty(fixture("stack_5"));
    s.bodies.resize(2);
    s.solver.penalty.stiffness = k;
    s.collision.reduce_to_four = reduce;
    s.bodies[1].frame.orientation = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()));
    World w(s);
    run(w, 3.0);
    return 1.0 - (w.bodies()[1].x.z() - w.bodies()[0].x.z());
  };
  const double m = 1.0;
  CHECK(sink_between(0.0, false) == Approx(m * kG / (4.0 * k)).epsilon(1e-6));
  CHECK(sink_between(M_PI / 4.0, false) == Approx(m * kG / (8.0 * k)).epsilon(1e-6));
  CHECK(sink_between(M_PI / 4.0, true) == Approx(m * kG / (4.0 * k)).epsilon(1e-6));
}
