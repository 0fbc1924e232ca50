// Two-sample tests: whether two samples of an outcome (each engine's runs from perturbed starts,
// validation/accuracy/outcomes.hpp) come from one distribution. The Kolmogorov-Smirnov test compares the
// whole distributions (exact p-value by counting lattice paths for small samples, Kolmogorov's
// limit with Stephens' correction for large ones); Welch's t test compares the means without
// assuming equal spreads. docs/accuracy.md, "Chaotic scenes", says how the verdicts use them.
#pragma once

#include <vector>

namespace boxpile {

struct SampleSummary {
  int n = 0;
  double mean = 0.0;
  double sd = 0.0;  // the sample standard deviation (n - 1 in the denominator; 0 for n < 2)
  double min = 0.0, max = 0.0;
};
SampleSummary summarize(const std::vector<double>& x);

struct KsResult {
  double statistic = 0.0;  // D: the largest distance between the two empirical distribution functions
  double p_value = 1.0;    // P(D >= observed) when both samples come from one continuous distribution
  bool exact = false;      // counted over the lattice paths (else Kolmogorov's limit)
};
// Empty samples: D = 0, p = 1.
KsResult kolmogorov_smirnov(const std::vector<double>& a, const std::vector<double>& b);

// The exact two-sided p-value P(D_{n,m} >= d) of the two-sample statistic under the null, without
// ties: the share of the C(n + m, n) orderings of the pooled sample whose path leaves the band
// |i/n - j/m| < d.
double ks_exact_p(double d, int n, int m);
// Kolmogorov's limit Q(lambda) = 2 sum_{k>=1} (-1)^(k-1) exp(-2 k^2 lambda^2), in [0, 1].
double kolmogorov_q(double lambda);

struct WelchResult {
  double t = 0.0;        // (mean_a - mean_b) / sqrt(s_a^2 / n_a + s_b^2 / n_b)
  double df = 0.0;       // Welch-Satterthwaite degrees of freedom
  double p_value = 1.0;  // two-sided
};
// Both spreads 0: p = 1 for equal means, 0 for different ones (t and df then 0). Fewer than two
// values in a sample: p = 1.
WelchResult welch_t_test(const std::vector<double>& a, const std::vector<double>& b);

// The two-sided tail P(|T| >= t) of Student's t distribution with `df` degrees of freedom (df > 0).
double student_t_two_sided_p(double t, double df);
// The regularized incomplete beta function I_x(a, b), for a, b > 0 and x in [0, 1].
double regularized_incomplete_beta(double x, double a, double b);

}  // namespace boxpile
