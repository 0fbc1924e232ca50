// Stacks: groups of bodies that rest on the ground through one another, found through the contact
// graph from the ground, measured the same way for every engine (from body states posed on our
// bodies, with our own separating-axis test).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// Two bodies, or a body and the ground, touch when their gap is at most this. Resting contacts sit
// within a few micrometres in every engine (Bullet keeps points up to 0.017 m apart, but its
// bodies rest at depth >= 0); boxes placed apart on purpose (the pyramid's 0.02 m gaps) stay apart.
inline constexpr double kTouchTolerance = 1e-3;  // m

struct Stack {
  std::vector<int> bodies;  // scene indices, lowest first (by centre of mass along the normal)
  double height = 0.0;      // m, of the highest point of any of its boxes above the ground
  // m, when the stack is a column of single boxes (the lowest on the ground, each of the others on
  // the one below it and touching no other): the sum of the boxes' heights, each box's edge along
  // its axis nearest the ground normal (a box lying on a face). Empty for any other stack.
  std::optional<double> column_height;
};

// The stacks of a pose: the connected groups of the graph whose nodes are the free bodies and
// whose edges join touching bodies, that contain at least one body touching the ground. Bodies
// on a wire hang rather than rest and fixed bodies never move, so neither joins a stack. A scene
// without ground has no stacks. Stacks are ordered by their lowest body index.
std::vector<Stack> find_stacks(const std::vector<RigidBody>& bodies, const Scene& scene,
                               double tolerance = kTouchTolerance);

// Height of a body's highest point above the ground plane (n . x - offset).
double top_height(const RigidBody& body, const HalfSpace& ground);

// A stack at the end of a run, and what it should be: `ideal` is its height at the start when the
// same bodies formed a stack at the start (a scene that started as a stack), else its column
// height when it is a column of boxes (boxes dropped onto each other), else empty.
struct StackReport {
  std::vector<std::string> bodies;  // names, lowest first
  double height = 0.0;              // m
  std::optional<double> ideal;      // m
  std::optional<double> error;      // m, height - ideal
};

std::vector<StackReport> report_stacks(const std::vector<Stack>& final_stacks,
                                       const std::vector<Stack>& start_stacks,
                                       const std::vector<RigidBody>& bodies);

}  // namespace boxpile
