#include "boxpile/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace boxpile {

namespace {
// What one pair's box-box or box-plane test costs, roughly (a microsecond on the benchmark's pairs),
// and the pairs the contact search hands a worker at a time: taking an item costs some tens of
// nanoseconds.
constexpr double kPairTestSeconds = 1e-6;
constexpr int kPairsPerItem = 8;

// What the workers could take over from the caller when the search shares `pairs` tests: every
// item but the first.
double shareable_pair_seconds(std::size_t pairs) {
  return static_cast<double>(std::max<std::size_t>(pairs, kPairsPerItem) - kPairsPerItem) * kPairTestSeconds;
}
}  // namespace

World::World(const Scene& scene, std::string name)
    : scene_(scene),
      name_(std::move(name)),
      bodies_(make_bodies(scene)),
      placed_(bodies_),
      wires_(make_wire_joints(scene, bodies_)),
      method_(make_contact_method(scene, bodies_)),
      pool_(resolve_threads(scene.solver.threads)) {
  ground_.name = "ground";
  ground_.fixed = true;
  ground_.material = scene.material;
  ground_.update_derived();
  margins_.resize(bodies_.size());
  base_margins_.resize(bodies_.size());
  bounds_.resize(bodies_.size());
  fixed_.resize(bodies_.size());
  for (const RigidBody& b : bodies_) {
    double r = 0.0;  // the farthest any box corner lies from the centre of mass
    for (const BoxShape& box : b.shapes) r = std::max(r, box.offset.norm() + box.half_extents.norm());
    bounding_radius_.push_back(r);
    smallest_edge_.push_back(smallest_edge(b));
  }
  const StepStorage storage{bodies_.size()};
  contacts_.reserve(storage.contacts());
  reuse_.reserve(bodies_.size(), storage.contacts(), storage.pairs() + bodies_.size(),
                 method_->reuses_contacts());
  events_.reserve(storage.events());
  broadphase_.reserve(storage);
  if (pool_.size() > 1) {
    found_.resize(static_cast<std::size_t>(pool_.size()));
    for (std::vector<BodyContact>& f : found_) f.reserve(storage.contacts());
    found_at_.reserve(storage.pairs() + bodies_.size());
  }
}

void World::step() {
  // The method's steps: each finds the contact set, then the method resolves it and advances.
  const int substeps = method_->substeps();
  const double h = scene_.time.dt / substeps;
  for (int k = 0; k < substeps; ++k) {
    counters_.profile.begin();
    find_contacts(h);
    counters_.profile.lap(Stage::contacts);
    StepContext ctx{scene_, bodies_,  ground_,  contacts_, reuse_.same_as_last_step(), wires_, time_ + k * h,
                    h,      counters_, events_, pool_};
    method_->step(ctx);
  }
  time_ += scene_.time.dt;
  ++counters_.steps;
}

void World::find_contacts(double dt) {
  reuse_.begin(bodies_, contacts_);
  update_margins(dt);
  placed_.place(bodies_);
  collide_body_pairs();
  collide_ground();
  counters_.pairs_found += static_cast<std::uint64_t>(reuse_.found_pairs());
  counters_.pairs_reused += static_cast<std::uint64_t>(reuse_.reused_pairs());
}

void World::update_margins(double dt) {
  // Each body's speculative margin: the contact margin (the scene's, or less for small boxes)
  // plus how far any of its points can move in one step, (|v| + |omega| r) dt, so that a fast body
  // meets what it would reach within the step as a speculative contact instead of tunnelling
  // into it. A pair gets the smaller of its two contact margins and both motions. Without
  // speculative contacts (the lab text's impulse method) only touching points are contacts.
  if (!method_->speculative_margins()) {
    std::fill(base_margins_.begin(), base_margins_.end(), 0.0);
    std::fill(margins_.begin(), margins_.end(), 0.0);
    return;
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    base_margins_[i] = std::max(scene_.collision.margin, contact_margin_for(scene_.solver, smallest_edge_[i]));
    margins_[i] = base_margins_[i] + (b.v.norm() + b.omega.norm() * bounding_radius_[i]) * dt;
  }
}

void World::collide_body_pairs() {
  // Bounding boxes from the boxes just placed, so that no body's pose is composed twice; the
  // fixed flags beside them, so that the sweep reads no body's whole state.
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    bounds_[i] = boxes_aabb(placed_.of(static_cast<int>(i)), margins_[i]);
    fixed_[i] = bodies_[i].fixed;
  }
  const std::vector<std::pair<int, int>>& pairs = broadphase_.find_pairs(bounds_, fixed_, scene_.max_pairs);
  if (pairs.size() > scene_.max_pairs) {
    // Each pair costs its contacts and their rows in the contact method: refused before the
    // narrowphase makes them (3,000 boxes at one point used to exhaust memory).
    throw std::runtime_error(name_ + ": step " + std::to_string(counters_.steps + 1) + ": more than " +
                             std::to_string(scene_.max_pairs) +
                             " pairs of bodies touch, above the cap on the pairs a step may make (--max-pairs "
                             "raises it)");
  }
  // The pairs' tests are shared among the threads only when there are enough of them to pay for
  // waking a worker (ThreadPool::shares); the contacts are the same either way.
  const bool ahead = pool_.shares(shareable_pair_seconds(pairs.size()));
  if (ahead) find_pairs_ahead(pairs);
  CollisionSettings cs = scene_.collision;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const int i = pairs[p].first, j = pairs[p].second;
    ++counters_.broadphase_pairs;
    cs.margin = pair_margin(i, j);
    reuse_.pair(i, j, cs.margin, contacts_, [&] {
      counters_.narrowphase_calls += bodies_[i].shapes.size() * bodies_[j].shapes.size();
      if (!ahead) {
        collide_bodies(placed_, i, j, cs, contacts_);
        return;
      }
      const FoundAt& at = found_at_[p];
      const auto from = found_[static_cast<std::size_t>(at.worker)].begin() + at.first;
      contacts_.insert(contacts_.end(), from, from + at.count);
    });
  }
}

void World::find_pairs_ahead(const std::vector<std::pair<int, int>>& pairs) {
  // The same narrowphase calls as the search makes one by one, their contacts in the same order:
  // the set is the same whatever the number of threads.
  for (std::vector<BodyContact>& f : found_) f.clear();
  found_at_.assign(pairs.size(), FoundAt{});
  // In runs of kPairsPerItem pairs.
  const int count = static_cast<int>(pairs.size());
  pool_.run((count + kPairsPerItem - 1) / kPairsPerItem, [&](int item, int worker) {
    std::vector<BodyContact>& out = found_[static_cast<std::size_t>(worker)];
    CollisionSettings cs = scene_.collision;
    for (int p = item * kPairsPerItem; p < std::min(count, (item + 1) * kPairsPerItem); ++p) {
      const int i = pairs[static_cast<std::size_t>(p)].first, j = pairs[static_cast<std::size_t>(p)].second;
      cs.margin = pair_margin(i, j);
      if (reuse_.copies(i, j, cs.margin, static_cast<std::size_t>(p))) continue;
      const int first = static_cast<int>(out.size());
      collide_bodies(placed_, i, j, cs, out);
      found_at_[static_cast<std::size_t>(p)] = {worker, first, static_cast<int>(out.size()) - first};
    }
  }, shareable_pair_seconds(pairs.size()));
}

void World::collide_ground() {
  if (!scene_.ground) return;
  CollisionSettings cs = scene_.collision;
  for (int i = 0; i < static_cast<int>(bodies_.size()); ++i) {
    if (bodies_[i].fixed) continue;
    cs.margin = margins_[i];
    reuse_.pair(i, kGround, cs.margin, contacts_, [&] {
      counters_.narrowphase_calls += bodies_[i].shapes.size();
      collide_body_ground(placed_, i, *scene_.ground, cs, contacts_);
    });
  }
}

void World::body_states(std::vector<BodyState>& out) const {
  out.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    const Pose frame = b.frame_pose();
    out[i] = {b.name, frame.position, frame.orientation, b.v, b.omega};
  }
}

}  // namespace boxpile
