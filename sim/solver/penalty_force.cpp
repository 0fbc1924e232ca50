#include "boxpile/sim/solver/penalty_force.hpp"

#include <algorithm>

namespace boxpile {

PenaltyForce penalty_force(const PenaltyPoint& pt, Vec3& anchor, bool& sliding) {
  PenaltyForce out;
  const Vec3& n = pt.n;
  const double un = n.dot(pt.u);
  out.normal = std::max(0.0, pt.stiffness * pt.depth - pt.damping * un);
  out.force = out.normal * n;
  if (pt.friction_stiffness <= 0.0 || pt.static_mu <= 0.0) return out;

  const Vec3 offset = pt.p - anchor;
  const Vec3 stretch = offset - n.dot(offset) * n;  // tangential, m
  const double spring = pt.friction_stiffness * stretch.norm();
  const double kinetic = pt.dynamic_mu * out.normal;
  const Vec3 ut = pt.u - un * n;
  // Sliding continues while the point still moves away from its anchor and the spring, dragged
  // along, pulls at least mu_d f_n; sticking ends when the spring pulls more than mu_s f_n.
  sliding = sliding ? spring >= kinetic && stretch.dot(ut) > 0.0 : spring > pt.static_mu * out.normal;
  if (sliding) {
    out.slipped = true;
    if (spring > 0.0) {
      const Vec3 dir = stretch / stretch.norm();
      anchor = pt.p - (kinetic / pt.friction_stiffness) * dir;  // the spring now pulls mu_d f_n
      out.force -= kinetic * dir;
    }
    return out;
  }
  Vec3 ft = -pt.friction_stiffness * stretch - pt.damping * ut;
  const double limit = pt.static_mu * out.normal;
  if (ft.norm() > limit) ft *= limit / ft.norm();  // the damper too stays within the cone
  out.force += ft;
  return out;
}

}  // namespace boxpile
