// Python bindings of interflatation/operators: box and grid interflatation (seed 001 §2.8, digest
// 001 §5 items 1 and 4) with Python callables as plane traces, Theorem 4 on plane regions (seed
// 001 §2.7) and Theorem 5 on bodies (seed 001 §2.8) with a Python target u and implicit,
// polygon or B-spline boundaries, their free traces fitted by least squares or min-max, and the
// tricubic grid interpolant.
#include "bindings.h"

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/operators/cubic_grid.h"
#include "interlin/interflatation/operators/free_traces.h"
#include "interlin/interflatation/operators/grid_interflatation.h"
#include "interlin/interflatation/operators/plane_boundary.h"
#include "interlin/interflatation/operators/region_interlineation.h"
#include "interlin/interflatation/operators/solid_interflatation.h"

#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>

namespace interlin::python {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

// Bit patterns of D coordinates: exact keys (NaN included) for the tables below.
template <int D>
using Key = std::array<std::uint64_t, D>;

template <int D>
struct KeyHash {
  size_t operator()(const Key<D>& k) const {
    size_t h = 0;
    for (std::uint64_t v : k)
      h = h * 1000003u ^ std::hash<std::uint64_t>()(v);
    return h;
  }
};

// A Python function f(x1, .., xD) of NumPy arrays -> array, called by an operator one point at
// a time. The operators ask for points that do not depend on the values returned, so a batch is
// evaluated in two passes: record() makes the operator's requests return 0 and remembers them,
// fetch() calls f once with every distinct point, and the second pass reads the table (a point
// missing from it is fetched on its own).
template <int D>
class BatchedFunction {
public:
  explicit BatchedFunction(py::function f) : f_{std::move(f)} {}

  double operator()(const std::array<double, D>& p) {
    const Key<D> k = key(p);
    if (recording_) {
      if (table_.emplace(k, 0.0).second)
        asked_.push_back(p);
      return 0;
    }
    const auto it = table_.find(k);
    if (it != table_.end())
      return it->second;
    asked_ = {p};
    fetch();
    return table_.at(k);
  }

  void record() {
    table_.clear();
    asked_.clear();
    recording_ = true;
  }

  // Calls f with every point asked for since record().
  void fetch() {
    recording_ = false;
    if (asked_.empty())
      return;
    const auto n = static_cast<py::ssize_t>(asked_.size());
    py::tuple args(D);
    for (int d = 0; d < D; ++d) {
      py::array_t<double> a(n);
      for (py::ssize_t i = 0; i < n; ++i)
        a.mutable_data()[i] = asked_[static_cast<size_t>(i)][static_cast<size_t>(d)];
      args[static_cast<size_t>(d)] = a;
    }
    const auto r = DoubleArray::ensure(f_.f(*args));
    if (!r || r.size() != n)
      throw py::value_error("a function of arrays must return one number per point (" +
                            std::to_string(n) + " asked, got " + std::to_string(r ? r.size() : 0) +
                            ")");
    for (py::ssize_t i = 0; i < n; ++i)
      table_[key(asked_[static_cast<size_t>(i)])] = r.data()[i];
    asked_.clear();
  }

private:
  static Key<D> key(const std::array<double, D>& p) {
    Key<D> k;
    for (int d = 0; d < D; ++d)
      k[static_cast<size_t>(d)] = std::bit_cast<std::uint64_t>(p[static_cast<size_t>(d)]);
    return k;
  }

  PythonCallable f_;
  bool recording_ = false;
  std::vector<std::array<double, D>> asked_;
  std::unordered_map<Key<D>, double, KeyHash<D>> table_;
};

// An operator with the batched Python functions it calls; coefficients: the free traces' c
// when fitted (fit_free_traces), else empty.
template <class Op, int D>
struct PythonOperator {
  Op op;
  std::vector<std::shared_ptr<BatchedFunction<D>>> functions;
  VectorXd coefficients;
};

// op at every row of P (N, dim): two passes (BatchedFunction). Output (N,).
template <class Op, int D, int Dim>
VectorXd evaluate_rows(PythonOperator<Op, D>& O, const MatrixXd& P, const char* name) {
  require_shape(P, Dim, name);
  using Point = Eigen::Matrix<double, Dim, 1>;
  VectorXd out(P.rows());
  for (const bool recording : {true, false}) {
    for (auto& f : O.functions)
      recording ? f->record() : f->fetch();
    for (Index i = 0; i < P.rows(); ++i)
      out(i) = evaluate(O.op, Point(P.row(i).transpose()));
  }
  return out;
}

// A Python callable as a batched function of D coordinates, for the C++ operator.
template <int D>
std::shared_ptr<BatchedFunction<D>> batched(const py::object& f) {
  if (!PyCallable_Check(f.ptr()))
    throw py::type_error("expected a callable of NumPy arrays");
  return std::make_shared<BatchedFunction<D>>(f.cast<py::function>());
}

// The operator O with its free traces u = w (1 + sum c_k phi_k) fitted to the Python target w
// at the rows of `samples` (free_traces.h). Two passes, as evaluate_rows: the fit asks for w at
// points that do not depend on w's values.
template <class Op, int D>
PythonOperator<Op, D> fit_python(const PythonOperator<Op, D>& O, const py::object& w,
                                 const MatrixXd& samples, const std::string& criterion) {
  require_shape(samples, D, "samples", 1);
  const TraceCriterion c = choice<TraceCriterion>(
      {{"least_squares", TraceCriterion::least_squares}, {"min_max", TraceCriterion::min_max}},
      criterion, "criterion");
  using Point = Eigen::Matrix<double, D, 1>;
  const Eigen::Matrix<double, Eigen::Dynamic, D> S = samples;
  PythonOperator<Op, D> out;
  auto b = batched<D>(w);
  out.functions.push_back(b);
  const std::function<double(const Point&)> wf = [b](const Point& p) {
    std::array<double, D> a;
    for (int d = 0; d < D; ++d)
      a[static_cast<size_t>(d)] = p(d);
    return (*b)(a);
  };
  b->record();
  fit_free_traces(O.op, wf, S, c);
  b->fetch();
  out.op = fit_free_traces(O.op, wf, S, c, &out.coefficients);
  return out;
}

// chords(args...) computed once per distinct key_of(args...) (thread-safe): Theorems 4 and 5
// ask for the same lines many times, and an implicit boundary given in Python costs hundreds of
// calls per line.
template <int N, class Chords, class KeyOf>
auto memoized(Chords chords, KeyOf key_of) {
  struct Cache {
    std::mutex m;
    std::unordered_map<Key<N>, std::vector<double>, KeyHash<N>> lines;
  };
  auto cache = std::make_shared<Cache>();
  return [chords = std::move(chords), key_of, cache](const auto&... args) {
    const Key<N> k = key_of(args...);
    {
      std::lock_guard<std::mutex> lock(cache->m);
      const auto it = cache->lines.find(k);
      if (it != cache->lines.end())
        return it->second;
    }
    std::vector<double> r = chords(args...);
    std::lock_guard<std::mutex> lock(cache->m);
    cache->lines.emplace(k, r);
    return r;
  };
}

// The chords of the line {p[axis] = c}, once per line.
PlaneBoundary cached(PlaneBoundary b) {
  b.chords = memoized<2>(std::move(b.chords), [](int axis, double c) {
    return Key<2>{static_cast<std::uint64_t>(axis), std::bit_cast<std::uint64_t>(c)};
  });
  return b;
}

const char* const kPlaneTracesDoc = R"(
nodes      [x, y, z]: per axis the increasing plane positions (>= 2 each)
traces     [on_x, on_y, on_z]: per axis one callable per plane; the trace on x = x_i is
           t(y, z), on y = y_j t(x, z), on z = z_k t(x, y), called with NumPy arrays of one
           shape and returning an array of that shape. Traces must agree where planes cross.
           interlin.plane_traces_from_function(u, nodes) builds them from u(x, y, z).
Call the operator with points P (N, 3) -> (N,). Each trace is called once per evaluation with
every point it is needed at.)";

void bind_grid(py::module_& m) {
  using Grid = PythonOperator<GridInterflatation, 2>;
  py::class_<Grid>(m, "GridInterflatation", R"(Interflatation on a grid of planes (seed 001 §2.8):
O = P1 + P2 + P3 - P1P2 - P1P3 - P2P3 + P1P2P3 with cardinal blending per axis, equal to u on
every grid plane; f - Of = (I - P1)(I - P2)(I - P3) f. O(P) for points P (N, 3) -> (N,).)")
      .def(
          "__call__",
          [](Grid& O, const MatrixXd& P) {
            return evaluate_rows<GridInterflatation, 2, 3>(O, P, "P");
          },
          py::arg("P"))
      .def_property_readonly("nodes", [](const Grid& O) {
        const auto& n = O.op.traces.nodes;
        return py::make_tuple(n[0], n[1], n[2]);
      });
  m.def(
      "grid_interflatation",
      [](const std::array<VectorXd, 3>& nodes, const std::array<std::vector<py::object>, 3>& traces,
         int degree) {
        Grid O;
        PlaneTraces t;
        t.nodes = nodes;
        for (int k = 0; k < 3; ++k)
          for (const py::object& f : traces[k]) {
            auto b = batched<2>(f);
            O.functions.push_back(b);
            t.traces[k].push_back([b](double a, double c) { return (*b)({a, c}); });
          }
        O.op = grid_interflatation(t, degree);
        return O;
      },
      py::arg("nodes"), py::arg("traces"), py::arg("degree") = 3,
      (std::string(R"(Grid interflatation -> GridInterflatation: degree 1 (per-box trilinear
Boolean sum, C0) or 3 (cubic cardinal splines, C2). ValueError for fewer than 2 planes per
axis, non-increasing nodes, a missing trace or another degree.)") +
       kPlaneTracesDoc)
          .c_str());
  m.def(
      "box_interflatation",
      [](const py::object& u, const Vector3d& lo, const Vector3d& hi, const MatrixXd& P) {
        PythonOperator<GridInterflatation, 3> O;
        auto b = batched<3>(u);
        O.functions.push_back(b);
        std::array<VectorXd, 3> nodes;
        for (int k = 0; k < 3; ++k)
          nodes[k] = Eigen::Vector2d(lo(k), hi(k));
        O.op = grid_interflatation(plane_traces(
                                       [b](const Vector3d& q) {
                                         return (*b)({q(0), q(1), q(2)});
                                       },
                                       nodes),
                                   1);
        return evaluate_rows<GridInterflatation, 3, 3>(O, P, "P");
      },
      py::arg("u"), py::arg("lo"), py::arg("hi"), py::arg("P"),
      R"(The box interflatation of u on [lo, hi] (trilinear Boolean sum, exact on the six faces;
digest 001 T14) at the points P (N, 3) -> (N,). u(x, y, z): NumPy arrays in, array out.)");
}

void bind_boundaries(py::module_& m) {
  py::class_<PlaneBoundary>(m, "PlaneBoundary", R"(A plane region G for Theorem 4: box (2, 2)
[[xmin, ymin], [xmax, ymax]] and chords(axis, c): the intervals (lo0, hi0, lo1, hi1, ...) of the
line {p[axis] = c} inside G. From implicit_boundary, polygon_boundary or curve_boundary.)")
      .def_property_readonly("box",
                             [](const PlaneBoundary& b) {
                               Eigen::Matrix2d r;
                               r << b.box.min().transpose(), b.box.max().transpose();
                               return r;
                             })
      .def(
          "chords",
          [](const PlaneBoundary& b, int axis, double c) {
            if (axis != 0 && axis != 1)
              throw py::value_error("axis: expected 0 (lines x = c) or 1 (lines y = c)");
            return b.chords(axis, c);
          },
          py::arg("axis"), py::arg("c"));
  const auto box2 = [](const MatrixXd& box) {
    if (box.rows() != 2 || box.cols() != 2)
      throw py::value_error("box: expected a (2, 2) array [[xmin, ymin], [xmax, ymax]]");
    return Eigen::AlignedBox2d(box.row(0).transpose(), box.row(1).transpose());
  };
  m.def(
      "implicit_boundary",
      [box2](py::function g, const MatrixXd& box, int samples) {
        const auto f = std::make_shared<PythonCallable>(PythonCallable{std::move(g)});
        return cached(implicit_boundary(
            [f](const Vector2d& p) {
              py::gil_scoped_acquire gil;
              return f->f(p(0), p(1)).cast<double>();
            },
            box2(box), samples));
      },
      py::arg("g"), py::arg("box"), py::arg("samples") = 512,
      R"(G = {g > 0} inside box (2, 2). g(x, y) is called with floats; the chords of a line are
the runs of g > 0 among `samples` points, their ends refined by bisection, computed once per line.)");
  m.def(
      "polygon_boundary",
      [](const MatrixXd& V) {
        require_shape(V, 2, "V", 3);
        return cached(polygon_boundary(V));
      },
      py::arg("V"), "G = the inside of the closed polygon V (#V, 2) (exact chords).");
  m.def(
      "curve_boundary",
      [](const BSplineCurve& curve, int samples_per_span) {
        return cached(curve_boundary(curve, samples_per_span));
      },
      py::arg("curve"), py::arg("samples_per_span") = 16,
      "G = the inside of a closed planar B-spline curve (e.g. a closed section curve).");
}

const char* cell_kind_name(CellKind k) {
  switch (k) {
  case CellKind::rectangle:
    return "rectangle";
  case CellKind::curved_top:
    return "curved_top";
  case CellKind::curved_bottom:
    return "curved_bottom";
  case CellKind::curved_left:
    return "curved_left";
  case CellKind::curved_right:
    return "curved_right";
  case CellKind::triangle:
    return "triangle";
  case CellKind::lens:
    return "lens";
  }
  return "?";
}

void bind_region(py::module_& m) {
  using Region = PythonOperator<RegionInterlineation, 2>;
  py::class_<Region>(m, "RegionInterlineation", R"(Theorem 4 of seed 001 (§2.7): the operator of a
plane region G on the grid lines x, y with the seed's zero substitution on dG. Ou = 0 on dG for
any u, Ou = u on every grid line inside G when u = 0 on dG, Ou = 0 outside G.
O(P) for points P (N, 2) -> (N,); O.trace(axis, c, s) the trace of line {p[axis] = c} at the
other coordinates s; O.cell_kinds() the pieces' kinds and their counts.)")
      .def(
          "__call__",
          [](Region& O, const MatrixXd& P) {
            return evaluate_rows<RegionInterlineation, 2, 2>(O, P, "P");
          },
          py::arg("P"))
      .def(
          "trace",
          [](Region& O, int axis, double c, const VectorXd& s) {
            if (axis != 0 && axis != 1)
              throw py::value_error("axis: expected 0 (lines x = c) or 1 (lines y = c)");
            VectorXd out(s.size());
            for (const bool recording : {true, false}) {
              for (auto& f : O.functions)
                recording ? f->record() : f->fetch();
              for (Index i = 0; i < s.size(); ++i)
                out(i) = line_trace(O.op, axis, c, s(i));
            }
            return out;
          },
          py::arg("axis"), py::arg("c"), py::arg("s"))
      .def("cell_kinds",
           [](const Region& O) {
             std::map<std::string, int> count;
             for (const auto& pieces : O.op.pieces)
               for (const CellPiece& p : pieces)
                 ++count[cell_kind_name(p.kind)];
             return count;
           })
      .def_readonly("coefficients", &Region::coefficients)
      .def_property_readonly("x", [](const Region& O) { return O.op.x; })
      .def_property_readonly("y", [](const Region& O) { return O.op.y; });
  m.def(
      "region_interlineation",
      [](const PlaneBoundary& boundary, const VectorXd& x, const VectorXd& y, const py::object& u,
         int samples) {
        Region O;
        auto b = batched<2>(u);
        O.functions.push_back(b);
        O.op = region_interlineation(
            boundary, x, y,
            [b](const Vector2d& p) {
              return (*b)({p(0), p(1)});
            },
            samples);
        return O;
      },
      py::arg("boundary"), py::arg("x"), py::arg("y"), py::arg("u"), py::arg("samples") = 16,
      R"(Theorem 4 operator -> RegionInterlineation.
boundary  a PlaneBoundary (implicit_boundary, polygon_boundary, curve_boundary)
x, y      increasing grid lines covering boundary.box (>= 2 each)
u(x, y)   the function whose restrictions are the free traces (NumPy arrays in, array out),
          e.g. the distance to dG or an R-function: Ou interpolates it on every grid line
samples   probes per cell for changes of the chord structure
ValueError for fewer than 2 lines, non-increasing lines or lines that do not cover the box.)");
}

// The chords of a line along `axis` clipped to [lo, hi], once per line and interval.
SolidBoundary cached(SolidBoundary b) {
  b.chords =
      memoized<5>(std::move(b.chords), [](int axis, const Vector3d& p, double lo, double hi) {
        const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
        return Key<5>{static_cast<std::uint64_t>(axis), std::bit_cast<std::uint64_t>(p(a1)),
                      std::bit_cast<std::uint64_t>(p(a2)), std::bit_cast<std::uint64_t>(lo),
                      std::bit_cast<std::uint64_t>(hi)};
      });
  return b;
}

// g as a function of a point: an Implicit (evaluated in C++) or a Python callable g(x, y, z)
// of floats.
std::function<double(const Vector3d&)> body_function(const py::object& g) {
  if (py::isinstance<ImplicitFunction>(g)) {
    const auto f = std::make_shared<const ImplicitFunction>(g.cast<ImplicitFunction>());
    return [f](const Vector3d& p) {
      Points3 P = p.transpose();
      VectorXd F(1);
      f->value(P, F);
      return F(0);
    };
  }
  if (!PyCallable_Check(g.ptr()))
    throw py::type_error("g: expected an Implicit or a callable g(x, y, z)");
  const auto f = std::make_shared<PythonCallable>(PythonCallable{g.cast<py::function>()});
  return [f](const Vector3d& p) {
    py::gil_scoped_acquire gil;
    return f->f(p(0), p(1), p(2)).cast<double>();
  };
}

const char* solid_kind_name(SolidCellKind k) {
  switch (k) {
  case SolidCellKind::box:
    return "box";
  case SolidCellKind::curved_box:
    return "curved_box";
  case SolidCellKind::pyramid:
    return "pyramid";
  case SolidCellKind::split:
    return "split";
  }
  return "?";
}

void bind_solid(py::module_& m) {
  py::class_<SolidBoundary>(m, "SolidBoundary", R"(A body G for Theorem 5: box (2, 3) and
chords(axis, p, lo, hi): the intervals (lo0, hi0, lo1, hi1, ...) of the line through p along
`axis` inside G, clipped to [lo, hi]. From solid_boundary.)")
      .def_property_readonly("box", [](const SolidBoundary& b) { return box_to_array(b.box); })
      .def(
          "chords",
          [](const SolidBoundary& b, int axis, const Vector3d& p, double lo, double hi) {
            if (axis < 0 || axis > 2)
              throw py::value_error("axis: expected 0, 1 or 2");
            return b.chords(axis, p, lo, hi);
          },
          py::arg("axis"), py::arg("p"), py::arg("lo"), py::arg("hi"));
  m.def(
      "solid_boundary",
      [](const py::object& g, const MatrixXd& box, int samples) {
        return cached(implicit_solid(body_function(g), box_from_array(box), samples));
      },
      py::arg("g"), py::arg("box"), py::arg("samples") = 8,
      R"(G = {g > 0} inside box (2, 3) [[xmin, ymin, zmin], [xmax, ymax, zmax]]. g: an Implicit
(e.g. rf.compile(...), load_model(...): evaluated in C++) or a callable g(x, y, z) of floats.
The chords of a line are the runs of g > 0 among `samples` points per cell side, their ends
refined by bisection, computed once per line. ValueError for samples < 2 or an empty box.)");

  using Solid = PythonOperator<SolidInterflatation, 3>;
  py::class_<Solid>(m, "SolidInterflatation", R"(Theorem 5 of seed 001 (§2.8): the interflatation
operator of a body G with grid planes and the seed's zero substitution on dG. Ou = 0 on dG for
any u (the implicit equation Ou = 0 of dG), Ou = u on every grid plane inside G when u = 0 on
dG, Ou = 0 outside G. O(P) for points P (N, 3) -> (N,); O.cell_kind(P) the kind of the piece
holding each point ("box", "curved_box", "pyramid", "split"); nodes; coefficients (the free
traces' c after fit_free_traces, one per grid node, x fastest; else empty).)")
      .def(
          "__call__",
          [](Solid& O, const MatrixXd& P) {
            return evaluate_rows<SolidInterflatation, 3, 3>(O, P, "P");
          },
          py::arg("P"))
      .def(
          "cell_kind",
          [](const Solid& O, const MatrixXd& P) {
            require_shape(P, 3, "P");
            std::vector<std::string> kinds;
            for (Index i = 0; i < P.rows(); ++i)
              kinds.emplace_back(solid_kind_name(cell_kind(O.op, P.row(i).transpose())));
            return kinds;
          },
          py::arg("P"))
      .def_property_readonly("nodes",
                             [](const Solid& O) {
                               const auto& n = O.op.nodes;
                               return py::make_tuple(n[0], n[1], n[2]);
                             })
      .def_readonly("coefficients", &Solid::coefficients);
  m.def(
      "solid_interflatation",
      [](const SolidBoundary& boundary, const std::array<VectorXd, 3>& nodes, const py::object& u,
         int mapping_axis, int samples) {
        Solid O;
        auto b = batched<3>(u);
        O.functions.push_back(b);
        O.op = solid_interflatation(
            boundary, nodes,
            [b](const Vector3d& p) {
              return (*b)({p(0), p(1), p(2)});
            },
            mapping_axis, samples);
        return O;
      },
      py::arg("boundary"), py::arg("nodes"), py::arg("u"), py::arg("mapping_axis") = -1,
      py::arg("samples") = 12,
      R"(Theorem 5 operator -> SolidInterflatation.
boundary      a SolidBoundary (solid_boundary)
nodes         [x, y, z]: per axis the increasing plane positions covering boundary.box (>= 2)
u(x, y, z)    the function whose restrictions are the traces (NumPy arrays in, array out), e.g.
              the distance to dG or an R-function: Ou interpolates it on every grid plane
mapping_axis  0, 1, 2: the chords' axis in every cell; -1: per cell, the axis with the fewest
              chord structures
samples       probes per cell side for the cross-sections
ValueError for fewer than 2 planes, non-increasing planes, planes that do not cover the box or a
mapping axis outside -1 .. 2.)");
  m.def(
      "fit_free_traces",
      [](const Solid& O, const py::object& w, const MatrixXd& samples,
         const std::string& criterion) { return fit_python(O, w, samples, criterion); },
      py::arg("O"), py::arg("w"), py::arg("samples"), py::arg("criterion") = "least_squares",
      R"(The free traces of Theorem 5 chosen by a criterion (seed 001 §2.8: rho(Ou, w) -> min):
u = w (1 + sum_k c_k phi_k), phi_k the trilinear hats of the grid nodes, c fitted at the points
`samples` (S, 3) of G: "least_squares" (min sum (Ou - w)^2) or "min_max" (min max |Ou - w|,
Lawson's iteration; never worse than c = 0 on the samples). O: built with u = w.
w(x, y, z): NumPy arrays in, array out. -> SolidInterflatation (c in .coefficients).)");
  m.def(
      "fit_free_traces",
      [](const PythonOperator<RegionInterlineation, 2>& O, const py::object& w,
         const MatrixXd& samples,
         const std::string& criterion) { return fit_python(O, w, samples, criterion); },
      py::arg("O"), py::arg("w"), py::arg("samples"), py::arg("criterion") = "least_squares",
      R"(The free traces of Theorem 4 chosen by a criterion (seed 001 §2.7): as above with the
bilinear hats of the grid nodes, samples (S, 2), w(x, y) -> RegionInterlineation.)");
}

void bind_cubic_grid(py::module_& m) {
  m.def(
      "cubic_grid",
      [](const py::array_t<double, py::array::f_style | py::array::forcecast>& values,
         const Vector3d& origin, double h) {
        if (values.ndim() != 3)
          throw py::value_error("values: expected an (n0, n1, n2) array of node values");
        const Eigen::Array3i n(int(values.shape(0)), int(values.shape(1)), int(values.shape(2)));
        // Fortran order: values[i, j, k] at i + n0 (j + n1 k), the grid's own order.
        const auto G = std::make_shared<CubicGrid>(cubic_grid(
            std::vector<double>(values.data(), values.data() + values.size()), origin, h, n));
        ImplicitFunction f;
        f.value = [G](const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> F) {
          for (Index i = 0; i < P.rows(); ++i)
            F(i) = evaluate(*G, P.row(i).transpose());
        };
        f.gradient = [G](const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> F,
                         Eigen::Ref<Points3> D) {
          Vector3d g;
          for (Index i = 0; i < P.rows(); ++i) {
            F(i) = evaluate(*G, P.row(i).transpose(), &g);
            D.row(i) = g.transpose();
          }
        };
        f.box = Eigen::AlignedBox3d(origin, grid_max(*G));
        return f;
      },
      py::arg("values"), py::arg("origin"), py::arg("h"),
      R"(The tricubic spline through node values (C2, natural ends): the fast form of the
spline-blended grid interflatation of node data. values (n0, n1, n2), values[i, j, k] at
origin + h (i, j, k), every n >= 2, h > 0 -> Implicit (value and exact gradient; box = the
nodes' box; outside it the nearest cell's polynomial).)");
}

} // namespace

void bind_interflatation(py::module_& m) {
  bind_grid(m);
  bind_boundaries(m);
  bind_region(m);
  bind_solid(m);
  bind_cubic_grid(m);
}

} // namespace interlin::python
