// The bodies as the resting phases (contact loop, shock propagation) see them: a compact array of
// what an impulse reads and writes (velocities, inverse mass, world inverse inertia), gathered
// from the bodies when a phase begins and scattered back when it ends. A RigidBody spreads this
// over several cache lines among its name, shapes and momenta; the phases' passes touch each
// body's velocities hundreds of times per step, each impulse waiting for the one before it.
#pragma once

#include <vector>

#include "boxpile/sim/body.hpp"
#include "boxpile/sim/collision/collide.hpp"
#include "boxpile/sim/math.hpp"
#include "boxpile/sim/solver/impulse.hpp"

namespace boxpile {

struct SolverBody {
  Vec3 P = Vec3::Zero();
  Vec3 L = Vec3::Zero();
  Vec3 v = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
  Mat3 inv_inertia = Mat3::Zero();  // world axes; zero for a fixed body and the ground
  double inv_mass = 0.0;            // zero for a fixed body and the ground
};

class SolverBodyArray {
 public:
  void reserve(std::size_t bodies) { body_.reserve(bodies + 1); }
  // Slots: the bodies and the ground's.
  std::size_t size() const { return body_.size(); }
  // Copies each body's velocities and inverse mass properties; slot 0 is the ground.
  void gather(const std::vector<RigidBody>& bodies);
  // Writes the velocities back, with the momenta they imply (P = m v, L = I omega), to every
  // body that is not fixed.
  void scatter(std::vector<RigidBody>& bodies) const;

  // Velocity of A's contact point relative to B's. omega x r as the product W omega with the
  // contact's W = [r]x^T (the same products and sums, so the same result to the bit): written as
  // cross products, the compiler assembled two of their scalars into a pair through the stack, and
  // the load waited on two stores it could not forward (perf: the hottest instruction of both
  // resting loops); as a product the pair comes out of registers.
  // The ground's point is at rest: a ground contact reads only A (the result is the same, up to
  // the sign of a zero).
  Vec3 relative_velocity(const SolverContact& c) const {
    const SolverBody& a = at(c.a);
    if (c.b == kGround) return a.v + c.Wa * a.omega;
    const SolverBody& b = at(c.b);
    return a.v + c.Wa * a.omega - b.v - c.Wb * b.omega;
  }
  // One body's velocities, momenta and inverse mass properties (kGround: the ground's slot).
  const SolverBody& state(int body) const { return at(body); }
  SolverBody& state(int body) { return at(body); }
  // Velocity of body's material point at the offset whose W = [r]x^T is given.
  Vec3 point_velocity(int body, const Mat3& W) const { return at(body).v + W * at(body).omega; }
  // Applies j to A and -j to B at the contact offsets, changing the velocities directly
  // (dv = j / m, d omega = I^-1 (r x j)). A fixed body or the ground has zero inverse mass and
  // inertia, so it does not move; a frozen body is left out by its flag.
  void apply(const SolverContact& c, const Vec3& j, bool a_moves = true, bool b_moves = true) {
    // Neither the ground nor a fixed body is pushed: its zero inverse mass would leave it at rest,
    // but its momenta would chain every contact's impulse on it to the one before, and islands
    // solved at once on several threads (islands.hpp) would all write them.
    if (a_moves && at(c.a).inv_mass != 0.0) push(at(c.a), j, c.ra);
    if (b_moves && c.b != kGround && at(c.b).inv_mass != 0.0) push(at(c.b), -j, c.rb);
  }

 private:
  // Body index (kGround = -1 for the ground) to its slot.
  const SolverBody& at(int body) const { return body_[static_cast<std::size_t>(body + 1)]; }
  SolverBody& at(int body) { return body_[static_cast<std::size_t>(body + 1)]; }
  static void push(SolverBody& body, const Vec3& j, const Vec3& r) {
    body.P += j;
    body.L += r.cross(j);
    body.v = body.inv_mass * body.P;
    body.omega = body.inv_inertia * body.L;
  }

  std::vector<SolverBody> body_;
};

}  // namespace boxpile
