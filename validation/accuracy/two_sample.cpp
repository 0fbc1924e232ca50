#include "boxpile/validation/accuracy/two_sample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace boxpile {
namespace {

// Samples up to this many values each get the exact lattice-path p-value (n m cells of work).
constexpr int kExactKsLargest = 500;
// A path point counts as reaching the observed D when within this of it (D is a difference of two
// fractions, computed in floating point).
constexpr double kKsTolerance = 1e-12;
// The continued fraction of the incomplete beta function: its steps and relative accuracy.
constexpr int kBetaFractionSteps = 300;
constexpr double kBetaFractionAccuracy = 1e-15;
constexpr double kBetaTiny = 1e-300;

double sample_mean(const std::vector<double>& x) {
  return x.empty() ? 0.0 : std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

double sample_variance(const std::vector<double>& x, double mean) {
  if (x.size() < 2) return 0.0;
  double s = 0.0;
  for (double v : x) s += (v - mean) * (v - mean);
  return s / static_cast<double>(x.size() - 1);
}

// The continued fraction of I_x(a, b) (modified Lentz), valid for x < (a + 1) / (a + b + 2).
double beta_fraction(double x, double a, double b) {
  double c = 1.0;
  double d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < kBetaTiny) d = kBetaTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= kBetaFractionSteps; ++m) {
    const double m2 = 2.0 * m;
    // The even step.
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + num * d;
    if (std::abs(d) < kBetaTiny) d = kBetaTiny;
    c = 1.0 + num / c;
    if (std::abs(c) < kBetaTiny) c = kBetaTiny;
    d = 1.0 / d;
    h *= d * c;
    // The odd step.
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + num * d;
    if (std::abs(d) < kBetaTiny) d = kBetaTiny;
    c = 1.0 + num / c;
    if (std::abs(c) < kBetaTiny) c = kBetaTiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < kBetaFractionAccuracy) break;
  }
  return h;
}

}  // namespace

SampleSummary summarize(const std::vector<double>& x) {
  SampleSummary s;
  s.n = static_cast<int>(x.size());
  if (x.empty()) return s;
  s.mean = sample_mean(x);
  s.sd = std::sqrt(sample_variance(x, s.mean));
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  s.min = *lo;
  s.max = *hi;
  return s;
}

double kolmogorov_q(double lambda) {
  if (!(lambda > 0.0)) return 1.0;
  // Below 0.2 the series converges slowly and Q is 1 to 15 digits.
  if (lambda < 0.2) return 1.0;
  double sum = 0.0;
  for (int k = 1; k <= 100; ++k) {
    const double term = std::exp(-2.0 * k * k * lambda * lambda);
    sum += (k % 2 == 1 ? term : -term);
    if (term < 1e-17) break;
  }
  return std::clamp(2.0 * sum, 0.0, 1.0);
}

double ks_exact_p(double d, int n, int m) {
  if (n <= 0 || m <= 0 || !(d > 0.0)) return 1.0;
  // inside[j]: the paths from (0, 0) to (i, j) that stay within the band, as a share of all
  // paths to that point (C(i + j, i)), so that the numbers stay within [0, 1] for any n, m.
  auto outside = [&](int i, int j) {
    return std::abs(static_cast<double>(i) / n - static_cast<double>(j) / m) >= d - kKsTolerance;
  };
  std::vector<double> share(static_cast<std::size_t>(m) + 1, 0.0);
  share[0] = 1.0;
  for (int j = 1; j <= m; ++j) share[j] = outside(0, j) ? 0.0 : share[j - 1];
  for (int i = 1; i <= n; ++i) {
    share[0] = outside(i, 0) ? 0.0 : share[0];
    for (int j = 1; j <= m; ++j) {
      if (outside(i, j)) {
        share[j] = 0.0;
        continue;
      }
      // Paths to (i, j) come from (i - 1, j), a share i / (i + j) of them, and from (i, j - 1).
      const double from_left = static_cast<double>(i) / (i + j);
      share[j] = from_left * share[j] + (1.0 - from_left) * share[j - 1];
    }
  }
  return std::clamp(1.0 - share[m], 0.0, 1.0);
}

KsResult kolmogorov_smirnov(const std::vector<double>& a, const std::vector<double>& b) {
  KsResult r;
  if (a.empty() || b.empty()) return r;
  std::vector<double> x = a, y = b;
  std::sort(x.begin(), x.end());
  std::sort(y.begin(), y.end());
  const double n = static_cast<double>(x.size()), m = static_cast<double>(y.size());
  std::size_t i = 0, j = 0;
  while (i < x.size() && j < y.size()) {
    // Step past every value equal to the smaller one in both samples (ties move together).
    const double v = std::min(x[i], y[j]);
    while (i < x.size() && x[i] == v) ++i;
    while (j < y.size() && y[j] == v) ++j;
    r.statistic = std::max(r.statistic, std::abs(static_cast<double>(i) / n - static_cast<double>(j) / m));
  }
  if (x.size() <= kExactKsLargest && y.size() <= kExactKsLargest) {
    r.p_value = ks_exact_p(r.statistic, static_cast<int>(x.size()), static_cast<int>(y.size()));
    r.exact = true;
  } else {
    const double ne = n * m / (n + m);
    const double root = std::sqrt(ne);
    r.p_value = kolmogorov_q((root + 0.12 + 0.11 / root) * r.statistic);
  }
  return r;
}

double regularized_incomplete_beta(double x, double a, double b) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front =
      std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(x, a, b) / a;
  return 1.0 - front * beta_fraction(1.0 - x, b, a) / b;
}

double student_t_two_sided_p(double t, double df) {
  if (!(df > 0.0) || std::isnan(t)) return std::numeric_limits<double>::quiet_NaN();
  if (std::isinf(t)) return 0.0;
  return std::clamp(regularized_incomplete_beta(df / (df + t * t), 0.5 * df, 0.5), 0.0, 1.0);
}

WelchResult welch_t_test(const std::vector<double>& a, const std::vector<double>& b) {
  WelchResult r;
  if (a.size() < 2 || b.size() < 2) return r;
  const double ma = sample_mean(a), mb = sample_mean(b);
  const double qa = sample_variance(a, ma) / static_cast<double>(a.size());
  const double qb = sample_variance(b, mb) / static_cast<double>(b.size());
  const double se2 = qa + qb;
  if (!(se2 > 0.0)) {
    r.p_value = ma == mb ? 1.0 : 0.0;
    return r;
  }
  r.t = (ma - mb) / std::sqrt(se2);
  r.df = se2 * se2 / (qa * qa / static_cast<double>(a.size() - 1) + qb * qb / static_cast<double>(b.size() - 1));
  r.p_value = student_t_two_sided_p(r.t, r.df);
  return r;
}

}  // namespace boxpile
