#pragma once
// Internal: the runs of a predicate along a segment, for the chords of implicit regions and
// bodies (plane_boundary.cpp, solid_interflatation.cpp).

#include <vector>

namespace interlin::detail {

// Bisection iterations: halving the sample spacing 60 times reaches round-off for any segment.
constexpr int kRunBisections = 60;

// The runs of inside(s) == true among `samples` (>= 2) equally spaced points of [lo, hi] (hi
// itself the last), as increasing pairs (start, end); ends between samples refined by bisection,
// a run at lo / hi starts / ends there. A run shorter than the sample spacing can be missed.
template <class Inside>
std::vector<double> sign_runs(const Inside& inside, double lo, double hi, int samples) {
  // The end of a run between s0 (inside when `in0`) and s1.
  const auto refine = [&](double s0, double s1, bool in0) {
    for (int k = 0; k < kRunBisections; ++k) {
      const double mid = 0.5 * (s0 + s1);
      (inside(mid) == in0 ? s0 : s1) = mid;
    }
    return in0 ? s0 : s1;
  };
  std::vector<double> out;
  double prev = lo;
  bool prev_in = inside(lo);
  if (prev_in)
    out.push_back(lo);
  for (int i = 1; i < samples; ++i) {
    const double s = i + 1 == samples ? hi : lo + (hi - lo) * i / (samples - 1);
    const bool in = inside(s);
    if (in != prev_in)
      out.push_back(refine(prev, s, prev_in));
    prev = s;
    prev_in = in;
  }
  if (prev_in)
    out.push_back(hi);
  return out;
}

} // namespace interlin::detail
