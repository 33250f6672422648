// Python bindings of interflatation/operators: box and grid interflatation (seed 001 §2.8, digest
// 001 §5 items 1 and 4) with Python callables as plane traces, Theorem 4 on plane regions (seed
// 001 §2.7) with a Python target u and implicit, polygon or B-spline boundaries, and the
// tricubic grid interpolant.
#include "bindings.h"

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/operators/cubic_grid.h"
#include "interlin/interflatation/operators/grid_interflatation.h"
#include "interlin/interflatation/operators/plane_boundary.h"
#include "interlin/interflatation/operators/region_interlineation.h"

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

// An operator with the batched Python functions it calls.
template <class Op, int D>
struct PythonOperator {
  Op op;
  std::vector<std::shared_ptr<BatchedFunction<D>>> functions;
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

// Chords of a boundary computed once per line (Theorem 4 asks for the same lines many times;
// an implicit boundary given in Python costs hundreds of calls per line).
PlaneBoundary cached(PlaneBoundary b) {
  struct Cache {
    std::mutex m;
    std::unordered_map<Key<2>, std::vector<double>, KeyHash<2>> lines;
  };
  auto cache = std::make_shared<Cache>();
  b.chords = [chords = std::move(b.chords), cache](int axis, double c) {
    const Key<2> k{static_cast<std::uint64_t>(axis), std::bit_cast<std::uint64_t>(c)};
    {
      std::lock_guard<std::mutex> lock(cache->m);
      const auto it = cache->lines.find(k);
      if (it != cache->lines.end())
        return it->second;
    }
    std::vector<double> r = chords(axis, c);
    std::lock_guard<std::mutex> lock(cache->m);
    cache->lines.emplace(k, r);
    return r;
  };
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
  bind_cubic_grid(m);
}

} // namespace interlin::python
