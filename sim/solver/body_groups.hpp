// Contacts sorted into groups that share no moving body, and the progress rule of passes that
// stop once they stall: what shock propagation and penetration recovery both do with a phase's
// contacts, so that each group leaves the passes once it has converged while another still runs.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace boxpile {

// The moving bodies of one contact of a phase: `first` always moves; `second` is the other body
// when it moves too (the contact links two moving bodies), else -1.
struct MovingBodies {
  int first = 0;
  int second = -1;
  // The moving bodies of a contact between bodies a and b, of which at least one moves.
  static MovingBodies of(int a, int b, bool a_moves, bool b_moves) {
    return a_moves ? MovingBodies{a, b_moves ? b : -1} : MovingBodies{b, -1};
  }
};

// Groups of a phase's contacts: two contacts are in one group when a chain of contacts between
// moving bodies joins their moving bodies (union-find). Groups are numbered in the order of their
// first contact, and each keeps its contacts in the phase's order, so a sort is the same whatever
// the union's tie-breaks.
class BodyGroups {
 public:
  void reserve(std::size_t bodies, std::size_t contacts) {
    root_.reserve(bodies);
    group_of_.reserve(bodies);
    start_.reserve(bodies + 1);
    fill_.reserve(bodies);
    roots_.reserve(bodies);
    contact_group_.reserve(contacts);
  }

  // Writes `contacts` into `grouped`, group by group. `moving(contact)` gives its MovingBodies;
  // `bodies` is the number of bodies of the step (every body index is below it).
  template <class Contact, class Moving>
  void sort(std::span<const Contact> contacts, std::size_t bodies, Moving moving, std::vector<Contact>& grouped) {
    // group_of_ is -1 for every body between sorts: set once per size, reset for the roots used.
    if (group_of_.size() != bodies) group_of_.assign(bodies, -1);
    root_.resize(bodies);
    for (const Contact& c : contacts) {
      const MovingBodies m = moving(c);
      root_[m.first] = m.first;
      if (m.second >= 0) root_[m.second] = m.second;
    }
    for (const Contact& c : contacts) {
      const MovingBodies m = moving(c);
      if (m.second < 0) continue;
      const int ra = find(m.first), rb = find(m.second);
      if (ra != rb) root_[std::max(ra, rb)] = std::min(ra, rb);
    }
    // A counting sort by group: each root numbered at its first contact (one find per contact).
    start_.assign(1, 0);
    roots_.clear();
    contact_group_.clear();
    for (const Contact& c : contacts) {
      const int root = find(moving(c).first);
      if (group_of_[root] < 0) {
        group_of_[root] = static_cast<int>(roots_.size());
        roots_.push_back(root);
        start_.push_back(0);
      }
      contact_group_.push_back(group_of_[root]);
      ++start_[group_of_[root] + 1];
    }
    for (std::size_t g = 1; g < start_.size(); ++g) start_[g] += start_[g - 1];
    grouped.resize(contacts.size());
    fill_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < contacts.size(); ++k)
      grouped[static_cast<std::size_t>(fill_[contact_group_[k]]++)] = contacts[k];
    for (const int root : roots_) group_of_[root] = -1;
  }

  // The number of groups of the last sort, and group g of what it wrote into `grouped`.
  int count() const { return static_cast<int>(start_.size()) - 1; }
  template <class Contact>
  std::span<const Contact> group(const std::vector<Contact>& grouped, int g) const {
    return {grouped.data() + start_[g], grouped.data() + start_[g + 1]};
  }

 private:
  int find(int body) {
    while (root_[body] != body) body = root_[body] = root_[root_[body]];  // path halving
    return body;
  }

  std::vector<int> root_;      // per body, its union-find parent among the phase's moving bodies
  std::vector<int> group_of_;  // per root body, its group (-1 between sorts)
  std::vector<int> start_, fill_;
  std::vector<int> roots_;          // per group, its root body
  std::vector<int> contact_group_;  // per contact of the sort, its group
};

// Whether a group's passes still converge: a pass makes progress when its largest change falls
// below `factor` times the smallest change of the earlier passes; after `patience` passes in a row
// without progress the passes are cycling (or only growing) and more would repeat them.
class PassProgress {
 public:
  PassProgress(double factor, int patience) : factor_(factor), patience_(patience) {}
  // Records a pass's largest change; false once the passes have stalled.
  bool made(double change) {
    if (change < factor_ * lowest_change_) {
      lowest_change_ = change;
      passes_without_progress_ = 0;
      return true;
    }
    return ++passes_without_progress_ < patience_;
  }

 private:
  double factor_;
  int patience_;
  double lowest_change_ = std::numeric_limits<double>::infinity();
  int passes_without_progress_ = 0;
};

}  // namespace boxpile
