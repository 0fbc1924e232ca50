#include "boxpile/sim/solver/recovery.hpp"

#include <algorithm>
#include <cmath>

namespace boxpile {

namespace {
// A phase's passes stop once no pseudo-impulse changes a point's pseudo-velocity by more than
// would move the point this fraction of its contact's slop in the step: what is left is far
// inside the overlap recovery leaves alone, and the next step's recovery starts from it (a slop
// of 0 never converges early: every pass runs).
constexpr double kRecoveryConverged = 0.05;
// A shock level's group stalls when kRecoveryStallPasses passes in a row fail to bring the largest
// change below kRecoveryProgress of the smallest so far (a body wedged between two frozen ones,
// whose pseudo-impulses only grow): it stops, and the phase with every body movable, which
// follows, is the one that can free it.
constexpr double kRecoveryProgress = 0.95;
constexpr int kRecoveryStallPasses = 3;
}  // namespace

// The separating pseudo-velocity a contact asks for, beyond what the resolved velocities already
// give it. A contact deeper than the slop asks for beta of its overlap beyond the slop per step,
// plus whatever approach the resolved velocities still leave at it. A shallower one asks only
// that the pair end the step no deeper than the slop: it holds against pseudo-velocities that
// would push its bodies into each other, and covers an approach the velocity stages left (a body
// frozen by shock propagation that drives into the level above it, an impact the collision loop
// had no passes left for). Pseudo-velocities move positions only, so covering an approach adds
// no kinetic energy: the momenta keep it, and the next step's loops resolve it (when they are cut
// short, that energy stays instead of being paid for by the bodies sinking: docs/solver.md).
double PenetrationRecovery::pseudo_target(const SolverBodyArray& sb, const SolverContact& c, double beta, double dt) {
  const double un = c.n.dot(sb.relative_velocity(c));
  if (c.depth > c.slop) return beta * (c.depth - c.slop) / dt + std::max(0.0, -un);
  return -(c.slop - c.depth) / dt - un;
}

void PenetrationRecovery::reserve(const StepStorage& storage) {
  pseudo_v_.reserve(storage.bodies);
  pseudo_omega_.reserve(storage.bodies);
  pushed_.reserve(storage.bodies);
  lambda_.reserve(storage.contacts());
  normal_mass_.reserve(storage.contacts());
  target_.reserve(storage.contacts());
  all_.reserve(storage.contacts());
  own_.reserve(storage);
}

void PenetrationRecovery::Worker::reserve(const StepStorage& storage) {
  phase.reserve(storage.contacts());
  grouped.reserve(storage.contacts());
  groups.reserve(storage.bodies, storage.contacts());
}

void PenetrationRecovery::run(const ImpulseStep& step, const ShockPropagation* shock) {
  step.resting.gather(step.sb.bodies);
  if (prepare(step)) solve_island(step, shock, 0, static_cast<int>(step.contacts.size()), own_);
}

bool PenetrationRecovery::prepare(const ImpulseStep& step) {
  const std::vector<SolverContact>& contacts = step.contacts;
  const double beta = step.settings().penetration_recovery;
  const std::size_t n = step.sb.bodies.size();
  pseudo_v_.assign(n, Vec3::Zero());
  pseudo_omega_.assign(n, Vec3::Zero());
  pushed_.assign(n, 0);
  lambda_.assign(contacts.size(), 0.0);
  own_.skipped_phases = 0;
  target_.resize(contacts.size());
  all_.clear();
  bool any_push = false;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    target_[k] = pseudo_target(step.resting, contacts[k], beta, step.dt());
    any_push = any_push || target_[k] > 0.0;
    all_.push_back(static_cast<int>(k));
  }
  if (!any_push) return false;  // nothing overlaps beyond the slop or approaches: no pseudo-velocity
  normal_mass_.assign(contacts.size(), kNormalMassUnset);
  return true;
}

void PenetrationRecovery::solve_island(const ImpulseStep& step, const ShockPropagation* shock, int begin, int end,
                                       Worker& worker) {
  // The island's contacts among a list of contact indices in increasing order.
  auto within = [&](std::span<const int> list) {
    const auto first = std::lower_bound(list.begin(), list.end(), begin);
    const auto last = std::lower_bound(first, list.end(), end);
    return list.subspan(static_cast<std::size_t>(first - list.begin()), static_cast<std::size_t>(last - first));
  };
  // With shock propagation's levels, first each level from the ground up with the lower ones
  // frozen, as the velocities were: a body on top cannot push the bodies under it into the
  // ground, and a lower body the velocity stages left driving into the one above it moves that
  // one out of its way. Then every contact with both bodies movable: in a tumbling pile a
  // body's level (its distance from the ground in the contact graph) need not follow its
  // height, and a frozen lower level may hold what the level above it must push (with the levels
  // alone, a pair of `pile_100` sank 5 cm over 80 steps).
  if (shock)
    for (int l = 0; l <= shock->top_level(); ++l) solve_phase(step, within(shock->contacts_of_level(l)), shock, l, worker);
  solve_phase(step, within(all_), nullptr, 0, worker);
}

void PenetrationRecovery::solve_phase(const ImpulseStep& step, std::span<const int> contacts,
                                      const ShockPropagation* shock, int level, Worker& worker) {
  // A phase none of whose contacts may change would skip every contact in its first pass and stop
  // there: it is skipped whole (most often a low level of a pile, left as the velocities had it).
  const auto can_change = [&](int k) { return may_change(k, step.contacts[k].a, step.contacts[k].b); };
  if (skip_idle_phases_ && std::none_of(contacts.begin(), contacts.end(), can_change)) {
    ++worker.skipped_phases;
    return;
  }
  collect_phase(step, contacts, shock, level, worker.phase);
  // A contact moves the body it pushes that is not frozen; one between two of them links their
  // groups.
  auto moving = [](const PhaseContact& pc) { return MovingBodies::of(pc.a, pc.b, pc.a_moves, pc.b_moves); };
  worker.groups.sort(std::span<const PhaseContact>(worker.phase), step.sb.bodies.size(), moving, worker.grouped);
  for (int g = 0; g < worker.groups.count(); ++g)
    solve_group(step, worker.groups.group(worker.grouped, g), shock != nullptr);
}

void PenetrationRecovery::collect_phase(const ImpulseStep& step, std::span<const int> contacts,
                                        const ShockPropagation* shock, int level, std::vector<PhaseContact>& phase_) {
  const SolverBodies& sb = step.sb;
  // With the levels, the level's own bodies (shock propagation's rule); without, every body
  // that is not fixed.
  auto moves = [&](int body) { return shock ? shock->moves(body, level) : body >= 0 && !sb.get(body).fixed; };
  // Each contact with what its passes read: which bodies move, and 1 / (n . K n) over them.
  phase_.clear();
  for (const int k : contacts) {
    const SolverContact& c = step.contacts[k];
    const bool a_moves = moves(c.a), b_moves = moves(c.b);
    if (!a_moves && !b_moves) continue;  // nothing it could push
    const double k_nn = normal_mass(step, k, a_moves, b_moves);
    if (k_nn > 0.0) phase_.push_back({k, c.a, c.b, a_moves, b_moves, 1.0 / k_nn, k_nn * step.dt() / c.slop});
  }
}

double PenetrationRecovery::normal_mass(const ImpulseStep& step, int k, bool a_moves, bool b_moves) {
  const Vec3& n = step.contacts[static_cast<std::size_t>(k)].n;
  const ContactMatrices& m = step.matrices[static_cast<std::size_t>(k)];
  double& cached = normal_mass_[static_cast<std::size_t>(k)][(a_moves ? 1 : 0) + (b_moves ? 2 : 0) - 1];
  // The sum as the phases formed it before, without adding a zero share: the same to the last bit.
  if (std::isnan(cached))
    cached = a_moves && b_moves ? n.dot((m.Ka + m.Kb) * n) : n.dot((a_moves ? m.Ka : m.Kb) * n);
  return cached;
}

void PenetrationRecovery::solve_group(const ImpulseStep& step, std::span<const PhaseContact> group, bool stop_stalled) {
  const SolverBodies& sb = step.sb;
  auto point_velocity = [&](int body, const Vec3& r) -> Vec3 {
    return body < 0 ? Vec3::Zero() : Vec3(pseudo_v_[body] + pseudo_omega_[body].cross(r));
  };
  auto push = [&](int body, const Vec3& impulse, const Vec3& r) {
    const RigidBody& b = sb.get(body);
    pseudo_v_[body] += b.inv_mass * impulse;
    pseudo_omega_[body] += b.inv_inertia_world * r.cross(impulse);
    pushed_[body] = 1;
  };
  // The group's passes until it converges: groups share no moving body, so one converged stops
  // while another still runs.
  PassProgress progress(kRecoveryProgress, kRecoveryStallPasses);
  for (int pass = 0; pass < step.settings().recovery_passes; ++pass) {
    double largest_change = 0.0;  // |pseudo-velocity change| dt / slop
    for (const PhaseContact& pc : group) {
      // A contact that asks for no push and has none, between bodies nothing has pushed yet, would
      // stay at zero: skipped (most of a pile's resting contacts in the first passes).
      if (!may_change(pc.index, pc.a, pc.b)) continue;
      const SolverContact& c = step.contacts[pc.index];
      // Normal-only: lambda += (target - u_n) / (n . K n), kept >= 0 (pushes only).
      const double un = c.n.dot(point_velocity(c.a, c.ra) - point_velocity(c.b, c.rb));
      const double lambda = std::max(0.0, lambda_[pc.index] + (target_[pc.index] - un) * pc.inv_k_nn);
      const double change = lambda - lambda_[pc.index];
      if (change == 0.0) continue;
      // The change's velocity over the step, in slops: |change| (n . K n) dt / slop.
      largest_change = std::max(largest_change, std::abs(change) * pc.change_scale);
      lambda_[pc.index] = lambda;
      const Vec3 impulse = change * c.n;
      if (pc.a_moves) push(c.a, impulse, c.ra);
      if (pc.b_moves) push(c.b, -impulse, c.rb);
    }
    if (largest_change < kRecoveryConverged) break;
    if (stop_stalled && !progress.made(largest_change)) break;
  }
}

}  // namespace boxpile
