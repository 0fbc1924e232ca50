// Bounds shared by the reference engines' settings tables.
#pragma once

namespace boxpile::reference_limits {

// Iteration counts of the reference engines: far above any useful value, low enough that a typo
// (1e9) is refused instead of running for hours.
inline constexpr double kMaxIterations = 100000;
// Largest distance or speed a setting may name: none of them has a meaningful value beyond.
inline constexpr double kMaxLength = 1e3;  // m (or m/s)

}  // namespace boxpile::reference_limits
