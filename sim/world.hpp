// Our simulator: a World built from a Scene. The world owns what every contact method shares
// (the bodies, the contact set, the integrators, the wires); the method that resolves the
// contacts is a stage chosen by the scene's `solver.method` (sim/solver/contact_method.hpp).
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/broadphase.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/collision/contact_reuse.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"
#include "boxpile/sim/step_storage.hpp"
#include "boxpile/sim/solver/contact_method.hpp"
#include "boxpile/sim/solver/step_context.hpp"
#include "boxpile/sim/solver/wire.hpp"
#include "boxpile/sim/thread_pool.hpp"

namespace boxpile {

class World final : public Engine {
 public:
  // `name` is what the engine reports ("own", or the name of the engine that forced a method).
  explicit World(const Scene& scene, std::string name = "own");

  std::string_view name() const override { return name_; }
  void step() override;
  double time() const override { return time_; }
  void body_states(std::vector<BodyState>& out) const override;
  void contacts(std::vector<BodyContact>& out) const override { out = contacts_; }
  const std::vector<CollisionEvent>* collision_events() const override { return &events_; }
  const WorldCounters* solver_counters() const override { return &counters_; }
  bool enable_profile() override {
    counters_.profile.enable(true);
    return true;
  }
  std::string_view contact_method() const override { return scene_.solver.method; }
  // The method's own record of its work (ContactMethod::diagnostics), as `run --out` writes it.
  nlohmann::json method_diagnostics() const { return method_->diagnostics(events_.size()); }
  const ContactMethod* solver_method() const override { return method_.get(); }
  // The method as the type it is, or none (the tests and benchmarks read its own counters).
  template <class M>
  const M* method_as() const {
    return dynamic_cast<const M*>(method_.get());
  }

  const std::vector<RigidBody>& bodies() const { return bodies_; }
  std::vector<RigidBody>& bodies() { return bodies_; }
  const WorldCounters& counters() const { return counters_; }
  const std::vector<CollisionEvent>& events() const { return events_; }
  const Scene& scene() const { return scene_; }
  const std::vector<WireJoint>& wires() const { return wires_; }
  // How many threads a step runs on (solver.threads; 0 in the scene: every core).
  int threads() const { return pool_.size(); }

 private:
  // The world's own stage: the contact set of a step of length dt, with speculative margins.
  void find_contacts(double dt);
  // Its parts: each body's margin for this step; body pairs through the broadphase; the ground.
  void update_margins(double dt);
  void collide_body_pairs();
  void collide_ground();
  // The contacts of every pair of `pairs` that the reuse will not copy, found on the pool's
  // threads ahead of the search, each into its worker's list (found_, found_at_).
  void find_pairs_ahead(const std::vector<std::pair<int, int>>& pairs);
  // A pair's margin: the smaller of its two contact margins and both motions.
  double pair_margin(int i, int j) const {
    return margins_[i] + margins_[j] - std::max(base_margins_[i], base_margins_[j]);
  }

  Scene scene_;
  std::string name_;
  std::vector<RigidBody> bodies_;
  RigidBody ground_;  // a fixed body standing for the half-space in the solver
  double time_ = 0.0;

  SweepAndPrune broadphase_;
  PlacedBoxes placed_;  // every body's boxes in the world, placed once per contact search
  std::vector<BodyContact> contacts_;
  ContactReuse reuse_;  // the contacts of bodies at rest, kept from the last step
  std::vector<WireJoint> wires_;
  std::unique_ptr<ContactMethod> method_;
  std::vector<double> margins_;          // per body, this step's speculative margin, m
  std::vector<double> bounding_radius_;  // per body, m
  std::vector<double> base_margins_;     // per body, the contact margin for its size, m
  std::vector<double> smallest_edge_;    // per body, its smallest box edge, m
  std::vector<Aabb> bounds_;             // per body, its bounding box grown by its margin
  std::vector<char> fixed_;              // per body, 1 when fixed, for the broadphase
  std::vector<CollisionEvent> events_;
  WorldCounters counters_;
  ThreadPool pool_;  // solver.threads threads, the caller's included
  // With more than one thread: per worker, the contacts it found ahead; per pair of the search,
  // the worker and the range of its list that hold that pair's contacts (count -1: not found
  // ahead, the reuse copies it).
  struct FoundAt {
    int worker = 0, first = 0, count = -1;
  };
  std::vector<std::vector<BodyContact>> found_;
  std::vector<FoundAt> found_at_;
};

}  // namespace boxpile
