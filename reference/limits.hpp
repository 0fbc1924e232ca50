// Bounds shared by the reference engines' settings tables.
#pragma once

#include "boxpile/sim/io/setting.hpp"

namespace boxpile::reference_limits {

// Iteration counts of the reference engines: far above any useful value, low enough that a typo
// (1e9) is refused instead of running for hours.
inline constexpr double kMaxIterations = 100000;
// Largest distance or speed a setting may name: none of them has a meaningful value beyond.
inline constexpr double kMaxLength = 1e3;  // m (or m/s)

// The speed below which an approach does not bounce, a setting of ODE (its contacts' bounce_vel)
// and of Bullet (m_restitutionVelocityThreshold) alike, declared once for both.
inline SettingInfo restitution_threshold_info() {
  return {"restitution_threshold", SettingInfo::Kind::Number, "m/s", "approach speeds below this do not bounce", 0,
          kMaxLength};
}

}  // namespace boxpile::reference_limits
