#include "arcpress/fit/count_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace arcpress {
namespace {

/// Directions modulo π (angles in [0, π)) as a union of closed intervals.
class DirectionSet {
 public:
  void reset() {
    set_.assign(1, {0.0, kPi});
  }
  bool empty() const { return set_.empty(); }
  /// Keeps the directions within `half` (rad) of `centre` (rad, any value) modulo π.
  void keep(double centre, double half) {
    if (half >= kPi / 2) return;
    double c = std::fmod(centre, kPi);
    if (c < 0) c += kPi;
    Interval allowed[2];
    int count = 0;
    if (c - half < 0) {
      allowed[count++] = {0.0, c + half};
      allowed[count++] = {c - half + kPi, kPi};
    } else if (c + half > kPi) {
      allowed[count++] = {0.0, c + half - kPi};
      allowed[count++] = {c - half, kPi};
    } else {
      allowed[count++] = {c - half, c + half};
    }
    next_.clear();
    for (const Interval& s : set_)
      for (int k = 0; k < count; ++k) {
        const double lo = std::max(s.lo, allowed[k].lo), hi = std::min(s.hi, allowed[k].hi);
        if (lo <= hi) next_.push_back({lo, hi});
      }
    set_.swap(next_);
  }

 private:
  struct Interval {
    double lo, hi;
  };
  std::vector<Interval> set_, next_;
};

}  // namespace

size_t min_primitive_count(std::span<const Vec2> pts, double band_mm) {
  const size_t n = pts.size() < 2 ? 0 : pts.size() - 1;  // moves
  if (n == 0) return 0;
  // The circles through vertex i and vertex j: by the left normal N (a unit vector, either
  // sign) at vertex i, the curvature is k = 2 d·N / |d|² (d from i to j). A vertex u (from i)
  // is within the band ε of such a circle when |k (|u|² − ε²) − 2 u·N| ≤ 2ε (exact, the full
  // circle), that is when |w·N| ≤ ε with w = d (|u|² − ε²) / |d|² − u: N lies within
  // asin(ε / |w|) of the direction square to w. k = 0 is the line through both.
  const double eps = band_mm;
  std::vector<size_t> best(n + 1, std::numeric_limits<size_t>::max());
  best[0] = 0;
  DirectionSet normals;
  for (size_t i = 0; i < n; ++i) {
    size_t killer = 0;  // the vertex that ended the last test from i: tried first
    for (size_t j = i + 1; j <= n; ++j) {
      if (best[i] + 1 >= best[j]) continue;
      const Vec2 d = pts[j] - pts[i];
      const double dd = d.squaredNorm();
      bool ok = true;
      if (j > i + 1 && dd > 0) {
        normals.reset();
        auto holds = [&](size_t m) {
          const Vec2 u = pts[m] - pts[i];
          const Vec2 w = d * ((u.squaredNorm() - eps * eps) / dd) - u;
          const double len = w.norm();
          if (len <= eps) return true;
          normals.keep(std::atan2(w.y(), w.x()) + kPi / 2, std::asin(eps / len));
          return !normals.empty();
        };
        if (killer > i && killer < j) ok = holds(killer);
        for (size_t m = j - 1; ok && m > i; --m) {
          if (m == killer) continue;
          if (!holds(m)) {
            ok = false;
            killer = m;
          }
        }
      }
      // (Back at vertex i, any circle through it is allowed: a bound may allow too much.)
      if (ok) best[j] = best[i] + 1;
    }
  }
  return best[n];
}

}  // namespace arcpress
