// Shock propagation of the Guendelman-Bridson-Fedkiw step (sec. 7 of the paper).
#pragma once

#include <algorithm>
#include <span>
#include <vector>

#include "boxpile/sim/solver/body_groups.hpp"
#include "boxpile/sim/solver/impulse_step.hpp"
#include "boxpile/sim/step_storage.hpp"

namespace boxpile {

// Shock propagation: bodies sorted into levels by contact-graph distance from the ground and
// fixed bodies; level by level from the bottom, up to `shock_passes` passes with e = 0 over the
// contacts that reach down from the level (fewer once the level has converged), with every
// lower level frozen (infinite mass). A level's contacts fall into groups that share no moving
// body; a group whose touching points can all stick is solved directly, and each other group
// leaves the passes once it has converged.
class ShockPropagation {
 public:
  // Sizes the graph, the levels and the queue for `storage.bodies` bodies and their contacts.
  void reserve(const StepStorage& storage);
  // `same_contacts`: the step's contact set is the last run's, contact for contact (every one kept
  // from the last step at its index: StepContext::same_as_last_step), so the graph, the levels and
  // each level's groups are the last run's too and are not formed again.
  // The whole contact set as one island.
  void run(ImpulseStep& step, bool same_contacts = false);
  // What a worker of a run keeps for itself while it solves an island: the groups not converged yet.
  struct Worker {
    std::vector<int> active;
  };
  // A run in parts: `prepare` forms the graph, the levels and every level's groups (or keeps the
  // last run's), then `solve_island` solves the contacts [begin, end) of the set, an island
  // (islands.hpp), level by level, on the compact bodies (step.resting, gathered), with `worker`'s
  // scratch. Islands share no moving body, so they may be solved at once on several threads, each
  // with a worker of its own, and give the same result in any order.
  void prepare(ImpulseStep& step, bool same_contacts);
  void solve_island(ImpulseStep& step, int begin, int end, Worker& worker);
  // Level of each body in the last run (-1: fixed; kUnsupported: not connected to the ground).
  const std::vector<int>& levels() const { return level_; }
  static constexpr int kUnsupported = 1 << 30;
  // The highest level of the last run (-1 when no body is supported), and the contacts of level
  // l (those whose higher body is on level l).
  int top_level() const { return top_; }
  std::span<const int> contacts_of_level(int l) const {
    return {by_level_.data() + level_start_[l], by_level_.data() + level_start_[l + 1]};
  }
  // Whether body moves while `level` is solved: only the level's own bodies do (lower levels are
  // frozen; fixed bodies and the ground never move).
  bool moves(int body, int level) const { return body >= 0 && level_of(body) == level; }
  // A contact of the level being solved, with what its passes read, set when the level begins.
  struct LevelContact {
    int index = 0;         // in step.contacts
    bool a_moves = false;  // whether A (B) belongs to the level; the other is frozen or fixed
    bool b_moves = false;
    double target = 0.0;   // the u_n it asks for
  };

 private:
  // The stages of a run: the contact graph between movable bodies, each body's level, the
  // contacts grouped by level, and the levels solved from the bottom up.
  void build_graph(const ImpulseStep& step);
  void assign_levels(const ImpulseStep& step);
  void group_contacts_by_level(const ImpulseStep& step);
  // The groups [first, last) of a level (an island's): their targets, then their passes.
  void solve_level(ImpulseStep& step, int level, int first, int last, Worker& worker);
  // The level's contacts sorted into groups that share no moving body, so that each group leaves
  // the passes once it has converged (a pyramid's boxes of one level touch only the
  // frozen level below: one group each); appended to the run's groups.
  void group_level(const ImpulseStep& step, int level);
  // The passes over groups [begin, end) of a level, each group until it converges, all of them
  // until they stall.
  void solve_groups(ImpulseStep& step, int group_begin, int group_end, Worker& worker);
  // The groups [begin, end) of bodies on frozen supports solved directly where every touching point
  // sticks (sticking_solve.hpp); the rest become the passes' active groups. Returns the largest
  // residual of a direct solve (m/s), or -1 when none was solved.
  double solve_sticking_groups(ImpulseStep& step, int group_begin, int group_end, std::vector<int>& active);
  // Sets K and its inverse of the contacts that reach a frozen body to the moving body's share.
  static void set_frozen_collision_matrices(ImpulseStep& step, std::span<const LevelContact> contacts);
  // The contacts of group g of the run.
  std::span<const LevelContact> group(int g) const {
    return {grouped_.data() + group_start_[g], grouped_.data() + group_start_[g + 1]};
  }

  int level_of(int body) const { return body < 0 ? -1 : level_[body]; }
  // A contact belongs to the higher of its two bodies' levels.
  int contact_level(const SolverContact& c) const { return std::max(level_of(c.a), level_of(c.b)); }
  // The normal velocity a contact of `level` asks for against a frozen body (see the .cpp).
  double frozen_target(const SolverBodyArray& sb, const SolverContact& c, int level) const;

  int top_ = -1;  // the highest level that holds a body
  std::vector<int> level_;
  std::vector<int> queue_;
  std::vector<int> adjacency_start_, adjacency_;  // contact graph, compressed rows
  std::vector<int> by_level_;                      // contact indices sorted by level
  std::vector<int> level_start_;
  std::vector<LevelContact> level_contacts_;
  std::vector<LevelContact> group_contacts_;  // level_contacts_ by group
  BodyGroups groups_;                         // the level's groups
  // Every level's groups of the run, level after level: the contacts by group (grouped_), where
  // each group begins in it (group_start_, one past the last group's end at the back), and each
  // level's first group (level_group_); kept for the next run when its contact set is the same.
  std::vector<LevelContact> grouped_;
  std::vector<int> group_start_;
  std::vector<int> level_group_;
  Worker own_;  // run's worker
};

}  // namespace boxpile
