#include "interlin/reconstruction/meshing/project_to_zero.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

constexpr long kChunk = 2048; // points per task: one batch call per iteration and chunk

bool inside(double v) {
  return v > 0;
}

// roots_on_segments for the rows [r0, r1), serially, with batched evaluations.
void roots_chunk(const ImplicitFunction& f, const Points3& A, const Points3& B,
                 const Eigen::VectorXd& FA, const Eigen::VectorXd& FB, const RootOptions& o,
                 long r0, long r1, Eigen::VectorXd& t_out) {
  const long n = r1 - r0;
  struct State {
    double ti, fi, wi; // inside end: parameter, value, Illinois working value
    double to, fo, wo; // outside end
    int last = -1;     // end replaced by the previous step (0 inside, 1 outside)
    int steps = 0;
    double width_before = 1; // bracket width three steps ago
    bool done = false;
  };
  std::vector<State> s(static_cast<size_t>(n));
  for (long r = 0; r < n; ++r) {
    const double fa = FA(r0 + r), fb = FB(r0 + r);
    if (inside(fa) == inside(fb))
      throw std::invalid_argument("roots_on_segments: segment " + std::to_string(r0 + r) +
                                  " has no sign change (" + std::to_string(fa) + ", " +
                                  std::to_string(fb) + ")");
    State& q = s[size_t(r)];
    if (inside(fa))
      q = {0, fa, fa, 1, fb, fb};
    else
      q = {1, fb, fb, 0, fa, fa};
    q.done = fa == 0 || fb == 0;
  }
  std::vector<long> active;
  std::vector<double> trial;
  Points3 P(n, 3);
  Eigen::VectorXd F(n);
  for (;;) {
    active.clear();
    trial.clear();
    for (long r = 0; r < n; ++r) {
      State& q = s[size_t(r)];
      const double width = std::abs(q.to - q.ti);
      if (q.done || width <= o.tolerance || q.steps >= o.max_evaluations)
        continue;
      // Every fourth step bisects unless the last three halved the bracket (regula falsi may move
      // one end twice before Illinois brings the other across); a bisection counts as its halving,
      // so the bracket halves at least every four steps.
      bool bisect = !std::isfinite(q.wi) || !std::isfinite(q.wo);
      if (q.steps % 4 == 3) {
        bisect = bisect || width > 0.5 * q.width_before;
        q.width_before = bisect ? 0.5 * width : width;
      }
      double t = 0.5 * (q.ti + q.to);
      if (!bisect) {
        const double rf = q.ti + q.wi * (q.to - q.ti) / (q.wi - q.wo);
        if (rf > std::min(q.ti, q.to) && rf < std::max(q.ti, q.to))
          t = rf;
      }
      // At least half the tolerance from either end (Dekker's minimum step): a converged
      // estimate then lands across the root and closes the bracket, instead of creeping to it.
      t = std::clamp(t, std::min(q.ti, q.to) + 0.5 * o.tolerance,
                     std::max(q.ti, q.to) - 0.5 * o.tolerance);
      active.push_back(r);
      trial.push_back(t);
      P.row(long(active.size()) - 1) = A.row(r0 + r) + t * (B.row(r0 + r) - A.row(r0 + r));
    }
    if (active.empty())
      break;
    const long m = long(active.size());
    f.value(P.topRows(m), F.head(m));
    for (long a = 0; a < m; ++a) {
      State& q = s[size_t(active[size_t(a)])];
      const double t = trial[size_t(a)], v = F(a);
      ++q.steps;
      if (inside(v)) {
        q.ti = t, q.fi = q.wi = v;
        if (q.last == 0)
          q.wo *= 0.5; // Illinois: the outside end stayed twice
        q.last = 0;
      } else {
        q.to = t, q.fo = q.wo = v;
        if (q.last == 1)
          q.wi *= 0.5;
        q.last = 1;
      }
      q.done = v == 0;
    }
  }
  for (long r = 0; r < n; ++r) {
    const State& q = s[size_t(r)];
    // The end with the smaller |F| (the outside value may be NaN: then the inside end).
    t_out(r0 + r) = std::abs(q.fo) < std::abs(q.fi) ? q.to : q.ti;
  }
}

// Unit outward directions at the rows of X: -grad F / |grad F| (zero where it vanishes or is not
// finite); central differences with step half_h(r) when f has no gradient.
Points3 directions(const ImplicitFunction& f, const Points3& X, const Eigen::VectorXd& half_h) {
  const long n = long(X.rows());
  Points3 G(n, 3);
  if (f.gradient) {
    Eigen::VectorXd F(n);
    f.gradient(X, F, G);
  } else {
    Points3 Q(6 * n, 3);
    for (long r = 0; r < n; ++r)
      for (int a = 0; a < 3; ++a)
        for (int s = 0; s < 2; ++s) {
          Q.row(6 * r + 2 * a + s) = X.row(r);
          Q(6 * r + 2 * a + s, a) += s ? half_h(r) : -half_h(r);
        }
    Eigen::VectorXd F(6 * n);
    f.value(Q, F);
    for (long r = 0; r < n; ++r)
      for (int a = 0; a < 3; ++a)
        G(r, a) = (F(6 * r + 2 * a + 1) - F(6 * r + 2 * a)) / (2 * half_h(r));
  }
  for (long r = 0; r < n; ++r) {
    const double len = G.row(r).norm();
    if (len > 0 && std::isfinite(len))
      G.row(r) /= -len;
    else
      G.row(r).setZero();
  }
  return G;
}

// A search of the points' chunks in parallel: search(r0, m) handles rows [r0, r0 + m) and returns
// how many it missed; the total missed. *moved, when given, is reset to all 0 first.
template <class Search>
long missed_over_chunks(long n, const RootOptions& o, std::vector<char>* moved, Search search) {
  std::vector<long> missed(size_t(detail::chunk_count(n, kChunk)), 0);
  if (moved)
    moved->assign(size_t(n), 0);
  detail::parallel_chunks(n, kChunk, o.threads, [&](long c, long r0, long r1) {
    missed[size_t(c)] = search(r0, r1 - r0);
  });
  long total = 0;
  for (long x : missed)
    total += x;
  return total;
}

// The end of a chunk's search. state per row of the chunk: 1 bracketed by the segment A -> B
// (values FA, FB), 2 already on the surface, 3 missed. Each bracketed row r0 + r of P moves to
// the root on its segment; (*moved)[r0 + r] is 1 for every row not missed. Returns the missed.
long finish_chunk(const ImplicitFunction& f, const std::vector<int>& state, const Points3& A,
                  const Points3& B, const Eigen::VectorXd& FA, const Eigen::VectorXd& FB,
                  const RootOptions& o, long r0, Eigen::MatrixXd& P, std::vector<char>* moved) {
  const long m = long(state.size());
  std::vector<long> idx;
  for (long r = 0; r < m; ++r)
    if (state[size_t(r)] == 1)
      idx.push_back(r);
  const long k = long(idx.size());
  Points3 SA(k, 3), SB(k, 3);
  Eigen::VectorXd SFA(k), SFB(k), t(k);
  for (long a = 0; a < k; ++a) {
    SA.row(a) = A.row(idx[size_t(a)]);
    SB.row(a) = B.row(idx[size_t(a)]);
    SFA(a) = FA(idx[size_t(a)]);
    SFB(a) = FB(idx[size_t(a)]);
  }
  if (k > 0)
    roots_chunk(f, SA, SB, SFA, SFB, o, 0, k, t);
  for (long a = 0; a < k; ++a)
    P.row(r0 + idx[size_t(a)]) = SA.row(a) + t(a) * (SB.row(a) - SA.row(a));
  if (moved)
    for (long r = 0; r < m; ++r)
      (*moved)[size_t(r0 + r)] = state[size_t(r)] != 3;
  return std::count(state.begin(), state.end(), 3);
}

} // namespace

Eigen::VectorXd roots_on_segments(const ImplicitFunction& f, const Points3& A, const Points3& B,
                                  const Eigen::VectorXd& FA, const Eigen::VectorXd& FB,
                                  const RootOptions& o) {
  if (!f.value)
    throw std::invalid_argument("roots_on_segments: the implicit function has no value");
  const long n = long(A.rows());
  if (B.rows() != n || FA.size() != n || FB.size() != n)
    throw std::invalid_argument("roots_on_segments: A, B, FA, FB must have the same rows");
  if (!(o.tolerance > 0) || o.max_evaluations < 1)
    throw std::invalid_argument("roots_on_segments: tolerance must be > 0, max_evaluations >= 1");
  Eigen::VectorXd t(n);
  detail::parallel_chunks(n, kChunk, o.threads, [&](long, long r0, long r1) {
    roots_chunk(f, A, B, FA, FB, o, r0, r1, t);
  });
  return t;
}

void project_edge_vertices(const ImplicitFunction& f, const RegularGrid& g,
                           const std::vector<EdgeVertex>& E, Eigen::MatrixXd& V,
                           const RootOptions& o) {
  const long n = long(E.size());
  if (V.rows() != n || V.cols() != 3)
    throw std::invalid_argument("project_edge_vertices: V must be #E by 3");
  Points3 A(n, 3), B(n, 3);
  Eigen::VectorXd FA(n), FB(n);
  const long nx = g.nodes(0), nxy = nx * g.nodes(1);
  for (long r = 0; r < n; ++r) {
    const EdgeVertex& e = E[size_t(r)];
    if (e.node < 0 || e.node >= g.size() || e.axis < 0 || e.axis > 2)
      throw std::invalid_argument("project_edge_vertices: edge " + std::to_string(r) +
                                  " is not on the grid");
    const long i = e.node % nx, j = (e.node / nx) % g.nodes(1), k = e.node / nxy;
    A.row(r) = g.point(i, j, k).transpose();
    B.row(r) = A.row(r);
    B(r, e.axis) += g.spacing(e.axis);
    FA(r) = e.f0;
    FB(r) = e.f1;
  }
  const Eigen::VectorXd t = roots_on_segments(f, A, B, FA, FB, o);
  for (long r = 0; r < n; ++r) {
    const double s = std::clamp(t(r), kEdgeClamp, 1 - kEdgeClamp);
    V.row(r) = A.row(r) + s * (B.row(r) - A.row(r));
  }
}

long project_along(const ImplicitFunction& f, Eigen::MatrixXd& P, const Eigen::MatrixXd& D,
                   const Eigen::VectorXd& h, const RootOptions& o, std::vector<char>* moved,
                   double reach, double scan_step) {
  if (!f.value)
    throw std::invalid_argument("project_along: the implicit function has no value");
  const long n = long(P.rows());
  if (P.cols() != 3 || D.rows() != n || D.cols() != 3 || h.size() != n)
    throw std::invalid_argument("project_along: P, D must be #P by 3 and h #P");
  if (!(h.array() > 0).all())
    throw std::invalid_argument("project_along: step lengths must be > 0");
  if (!(reach >= 1) || !(reach <= 1e6) || !(scan_step > 0) || !(reach / scan_step <= 1e7))
    throw std::invalid_argument("project_along: reach in [1, 1e6], scan_step > 0");
  const double kScanStep = scan_step; // seed 003 code: 10000 steps of 0.01 h (reach 100)
  const int kScanSteps = int(std::lround(reach / kScanStep));
  return missed_over_chunks(n, o, moved, [&](long r0, long m) {
    Points3 Q = P.middleRows(r0, m);
    Eigen::VectorXd F0(m);
    f.value(Q, F0);
    // Per point: unit direction times the step sign, bracket ends, state.
    Points3 dir(m, 3), A(m, 3), B(m, 3);
    Eigen::VectorXd FA(m), FB(m), step(m);
    std::vector<int> state(size_t(m), 0); // 0 searching, 1 bracketed, 2 done, 3 missed
    for (long r = 0; r < m; ++r) {
      const double len = D.row(r0 + r).norm();
      if (F0(r) == 0 || !(len > 0) || !std::isfinite(len)) {
        state[size_t(r)] = F0(r) == 0 ? 2 : 3;
        continue;
      }
      dir.row(r) = (inside(F0(r)) ? 1.0 : -1.0) / len * D.row(r0 + r);
      step(r) = h(r0 + r);
    }
    // The last point on the start's side: distance along dir and value.
    Eigen::VectorXd last_d = Eigen::VectorXd::Zero(m), last_f = F0;
    std::vector<long> active, idx;
    for (long r = 0; r < m; ++r)
      if (state[size_t(r)] == 0)
        active.push_back(r);
    Points3 T(m, 3);
    Eigen::VectorXd FT(m);
    // Round 0: one step h; rounds 1..10000: steps of 0.01 h from the start.
    for (int round = 0; round <= kScanSteps && !active.empty(); ++round) {
      const long k = long(active.size());
      for (long a = 0; a < k; ++a) {
        const long r = active[size_t(a)];
        const double d = round == 0 ? step(r) : kScanStep * round * step(r);
        T.row(a) = Q.row(r) + d * dir.row(r);
      }
      f.value(T.topRows(k), FT.head(k));
      idx.clear();
      for (long a = 0; a < k; ++a) {
        const long r = active[size_t(a)];
        if (inside(FT(a)) != inside(F0(r))) {
          A.row(r) = Q.row(r) + (round == 0 ? 0.0 : last_d(r)) * dir.row(r);
          FA(r) = round == 0 ? F0(r) : last_f(r);
          B.row(r) = T.row(a);
          FB(r) = FT(a);
          state[size_t(r)] = 1;
        } else if (round == kScanSteps) {
          state[size_t(r)] = 3;
        } else {
          if (round > 0) {
            last_d(r) = kScanStep * round * step(r);
            last_f(r) = FT(a);
          }
          idx.push_back(r);
        }
      }
      active.swap(idx);
    }
    return finish_chunk(f, state, A, B, FA, FB, o, r0, P, moved);
  });
}

Eigen::MatrixXd outward_directions(const ImplicitFunction& f, const Eigen::MatrixXd& P, double h,
                                   int threads) {
  if (P.cols() != 3)
    throw std::invalid_argument("outward_directions: P must be #P by 3");
  if (!f.gradient && !(h > 0))
    throw std::invalid_argument("outward_directions: difference step must be > 0");
  const long n = P.rows();
  Eigen::MatrixXd D(n, 3);
  detail::parallel_chunks(n, kChunk, threads, [&](long, long r0, long r1) {
    const long m = r1 - r0;
    D.middleRows(r0, m) = directions(f, P.middleRows(r0, m), Eigen::VectorXd::Constant(m, 0.5 * h));
  });
  return D;
}

long project_by_gradient_walk(const ImplicitFunction& f, Eigen::MatrixXd& P,
                              const Eigen::VectorXd& h, int max_steps, const RootOptions& o,
                              std::vector<char>* moved) {
  if (!f.value)
    throw std::invalid_argument("project_by_gradient_walk: the implicit function has no value");
  const long n = long(P.rows());
  if (P.cols() != 3 || h.size() != n)
    throw std::invalid_argument("project_by_gradient_walk: P must be #P by 3 and h #P");
  if (!(h.array() > 0).all() || max_steps < 1)
    throw std::invalid_argument("project_by_gradient_walk: steps must be > 0, max_steps >= 1");
  return missed_over_chunks(n, o, moved, [&](long r0, long m) {
    Points3 cur = P.middleRows(r0, m);
    Eigen::VectorXd F0(m), fcur(m);
    f.value(cur, F0);
    fcur = F0;
    std::vector<int> state(size_t(m), 0); // 0 walking, 1 bracketed, 2 on the surface, 3 missed
    Points3 A(m, 3), B(m, 3);
    Eigen::VectorXd FA(m), FB(m);
    std::vector<long> active;
    for (long r = 0; r < m; ++r) {
      if (F0(r) == 0)
        state[size_t(r)] = 2;
      else
        active.push_back(r);
    }
    for (int step = 0; step < max_steps && !active.empty(); ++step) {
      const long k = long(active.size());
      Points3 X(k, 3);
      Eigen::VectorXd half(k);
      for (long a = 0; a < k; ++a) {
        X.row(a) = cur.row(active[size_t(a)]);
        half(a) = 0.5 * h(r0 + active[size_t(a)]);
      }
      const Points3 D = directions(f, X, half);
      Points3 T(k, 3);
      for (long a = 0; a < k; ++a) {
        const long r = active[size_t(a)];
        T.row(a) = X.row(a) + (inside(F0(r)) ? 1.0 : -1.0) * h(r0 + r) * D.row(a);
      }
      Eigen::VectorXd FT(k);
      f.value(T, FT);
      std::vector<long> next;
      for (long a = 0; a < k; ++a) {
        const long r = active[size_t(a)];
        if (D.row(a).isZero(0)) {
          state[size_t(r)] = 3;
        } else if (inside(FT(a)) != inside(F0(r))) {
          A.row(r) = cur.row(r);
          FA(r) = fcur(r);
          B.row(r) = T.row(a);
          FB(r) = FT(a);
          state[size_t(r)] = 1;
        } else {
          cur.row(r) = T.row(a);
          fcur(r) = FT(a);
          next.push_back(r);
        }
      }
      active.swap(next);
    }
    for (long r : active)
      state[size_t(r)] = 3;
    return finish_chunk(f, state, A, B, FA, FB, o, r0, P, moved);
  });
}

} // namespace interlin
