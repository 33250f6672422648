// Python bindings of interlineation/: Coons, Hermite Coons and Gordon operators whose traces are
// Python callables (studies of functions of two variables) or B-spline curves; cardinal splines.
#include "bindings.h"

#include "interlin/interlineation/cardinal_splines.h"
#include "interlin/interlineation/coons_hermite.h"
#include "interlin/interlineation/gordon_surface.h"

#include <algorithm>
#include <memory>
#include <vector>

namespace interlin::python {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::VectorXd;

// A trace given by a Python callable t(s, d): the d-th derivative along the line at the
// coordinates s, an array (n,), returned as (n,) (scalar functions) or (n, dim). The operators
// ask for one coordinate at a time; before evaluating an operator at many points, prefetch()
// calls t once with every coordinate the trace will be asked for (a trace on a line x = x_i is
// asked at the points' y, a trace on y = y_j at their x), so the per-point requests are table
// look-ups. Requests outside the table call t with a one-element array.
class PythonTrace {
public:
  explicit PythonTrace(py::function f) : f_(std::move(f)) {}

  RowVectorXd operator()(double s, int d) const {
    if (d == d_ && s_.size() > 0) {
      const double* it = std::lower_bound(s_.data(), s_.data() + s_.size(), s);
      if (it != s_.data() + s_.size() && *it == s)
        return values_.row(it - s_.data());
    }
    return call(VectorXd::Constant(1, s), d).row(0);
  }

  // s: sorted, distinct coordinates.
  void prefetch(const VectorXd& s, int d) {
    values_ = call(s, d);
    s_ = s;
    d_ = d;
  }
  void clear() {
    s_.resize(0);
    values_.resize(0, 0);
    d_ = -1;
  }

private:
  MatrixXd call(const VectorXd& s, int d) const {
    const py::array_t<double> arg(s.size(), s.data());
    const auto r =
        py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(f_(arg, d));
    if (!r || r.ndim() < 1 || r.ndim() > 2 || r.shape(0) != s.size())
      throw py::value_error("a trace t(s, d) must return an array of shape (len(s),) or "
                            "(len(s), dim) of numbers");
    const Index dim = r.ndim() == 2 ? r.shape(1) : 1;
    return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        r.data(), s.size(), dim);
  }

  py::function f_;
  VectorXd s_;
  int d_ = -1;
  MatrixXd values_;
};

// An operator with the Python traces it calls: traces on lines x = x_i (asked at y) and on
// y = y_j (asked at x).
template <class Op>
struct PythonOperator {
  Op op;
  std::vector<std::shared_ptr<PythonTrace>> on_x_lines, on_y_lines;
};

// Traces from Python objects: callables, or B-spline curves (evaluated in C++).
std::vector<Trace> traces_of(const std::vector<py::object>& objects,
                             std::vector<std::shared_ptr<PythonTrace>>& python) {
  std::vector<Trace> traces;
  for (const py::object& o : objects) {
    if (py::isinstance<BSplineCurve>(o)) {
      traces.push_back(spline_trace(o.cast<BSplineCurve>()));
    } else if (py::isinstance<py::function>(o) || py::hasattr(o, "__call__")) {
      auto t = std::make_shared<PythonTrace>(o.cast<py::function>());
      python.push_back(t);
      traces.push_back([t](double s, int d) { return (*t)(s, d); });
    } else {
      throw py::type_error("a trace must be a callable t(s, d) or a BSplineCurve");
    }
  }
  return traces;
}

LineTraces line_traces(const VectorXd& x, const VectorXd& y, const std::vector<py::object>& on_x,
                       const std::vector<py::object>& on_y,
                       std::vector<std::shared_ptr<PythonTrace>>& x_lines,
                       std::vector<std::shared_ptr<PythonTrace>>& y_lines) {
  return {x, y, traces_of(on_x, x_lines), traces_of(on_y, y_lines)};
}

VectorXd sorted_unique(const double* v, py::ssize_t n) {
  std::vector<double> s(v, v + n);
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return Eigen::Map<const VectorXd>(s.data(), Index(s.size()));
}

// O^(dx,dy) at the points (x_k, y_k) (x, y of one shape, or one of them a single value).
// Output: x's shape for scalar traces, x's shape + (dim,) otherwise.
template <class Op>
py::array_t<double> evaluate_at(PythonOperator<Op>& O, const DoubleArray& x, const DoubleArray& y,
                                int dx, int dy, Index dim) {
  std::vector<py::ssize_t> shape = pair_shape(x, y, "x and y");
  const py::ssize_t n = std::max(x.size(), y.size());
  const bool bx = x.size() == 1, by = y.size() == 1;
  if (dim > 1)
    shape.push_back(dim);
  py::array_t<double> out(shape);
  struct Clear { // the tables hold only this call's coordinates
    PythonOperator<Op>& O;
    ~Clear() {
      for (auto& t : O.on_x_lines)
        t->clear();
      for (auto& t : O.on_y_lines)
        t->clear();
    }
  } clear{O};
  const VectorXd ys = sorted_unique(y.data(), y.size()), xs = sorted_unique(x.data(), x.size());
  for (auto& t : O.on_x_lines)
    t->prefetch(ys, dy);
  for (auto& t : O.on_y_lines)
    t->prefetch(xs, dx);
  double* o = out.mutable_data();
  for (py::ssize_t k = 0; k < n; ++k) {
    const RowVectorXd v = evaluate(O.op, x.data()[bx ? 0 : k], y.data()[by ? 0 : k], dx, dy);
    std::copy(v.data(), v.data() + dim, o + k * dim);
  }
  return out;
}

const char* const kEvaluateDoc = R"(O(x, y, dx=0, dy=0): d^(dx+dy) (O f) / dx^dx dy^dy at the points
(x[k], y[k]) (arrays of one shape, or one of them a scalar). Returns x's shape for scalar traces,
x's shape + (dim,) otherwise. Each Python trace is called once per evaluation with every
coordinate it is needed at.)";

const char* const kTracesDoc = R"(
x, y      increasing line positions (either may be empty: one family of lines)
on_x[i]   trace on the line x = x[i]: a callable t(s, d) -> d-th derivative of f(x[i], s) at the
          array s (shape (n,) for scalar f, (n, dim) for vector f), or a BSplineCurve in s
on_y[j]   trace on the line y = y[j]: t(s, d) -> d^d/ds^d f(s, y[j])
Traces must agree at the crossings (tolerance * max(1, |value|)), else ValueError naming the
crossing. interlin.traces_from_function(f, x, y) builds the traces of a function f(x, y, dx, dy).)";

void bind_gordon(py::module_& m) {
  using Gordon = PythonOperator<GordonSurface>;
  py::class_<Gordon>(m, "GordonOperator", R"(Gordon / Coons interlineation operator
O f = P_x f + P_y f - P_x P_y f (digest 001 §5.1), exact on every line of its grid.)")
      .def(
          "__call__",
          [](Gordon& O, const DoubleArray& x, const DoubleArray& y, int dx, int dy) {
            return evaluate_at(O, x, y, dx, dy, O.op.dim);
          },
          py::arg("x"), py::arg("y"), py::arg("dx") = 0, py::arg("dy") = 0, kEvaluateDoc)
      .def_property_readonly("x", [](const Gordon& O) { return O.op.traces.x; })
      .def_property_readonly("y", [](const Gordon& O) { return O.op.traces.y; })
      .def_property_readonly("dim", [](const Gordon& O) { return O.op.dim; })
      .def_property_readonly(
          "corners", [](const Gordon& O) { return O.op.corners; },
          "f(x_i, y_j) at the crossings, (#x * #y, dim), row i + #x * j.");

  m.def(
      "gordon",
      [](const VectorXd& x, const VectorXd& y, const std::vector<py::object>& on_x,
         const std::vector<py::object>& on_y, int degree, int degree_x, int degree_y,
         double period_x, double period_y, double tolerance) {
        Gordon O;
        const LineTraces t = line_traces(x, y, on_x, on_y, O.on_x_lines, O.on_y_lines);
        GordonOptions o;
        o.degree_x = degree_x > 0 ? degree_x : degree;
        o.degree_y = degree_y > 0 ? degree_y : degree;
        o.periodic_x = period_x > 0, o.period_x = period_x;
        o.periodic_y = period_y > 0, o.period_y = period_y;
        o.tolerance = tolerance;
        O.op = gordon_surface(t, o);
        return O;
      },
      py::arg("x"), py::arg("y"), py::arg("on_x"), py::arg("on_y"), py::arg("degree") = 3,
      py::arg("degree_x") = 0, py::arg("degree_y") = 0, py::arg("period_x") = 0.0,
      py::arg("period_y") = 0.0, py::arg("tolerance") = 1e-10,
      (std::string(R"(Gordon (spline-blended) interlineation, digest 001 §5.1: cardinal blending
splines of `degree` (1 C0 = composite Coons, 2 C1, 3 C2; degree_x/degree_y override per
direction); period_x/period_y > 0 make that direction periodic.)") +
       kTracesDoc)
          .c_str());
  m.def(
      "coons",
      [](const VectorXd& x, const VectorXd& y, const std::vector<py::object>& on_x,
         const std::vector<py::object>& on_y, double tolerance) {
        Gordon O;
        const LineTraces t = line_traces(x, y, on_x, on_y, O.on_x_lines, O.on_y_lines);
        O.op = t.x.size() == 2 && t.y.size() == 2 ? coons_bilinear(t, tolerance)
                                                  : coons_composite(t, tolerance);
        return O;
      },
      py::arg("x"), py::arg("y"), py::arg("on_x"), py::arg("on_y"), py::arg("tolerance") = 1e-10,
      (std::string(R"(Bilinearly blended Coons interlineation: seed 001 Theorem 3 on one cell
(two lines per family), composite Coons (hat blending, C0, O(h_x^2 h_y^2)) on a grid.)") +
       kTracesDoc)
          .c_str());
}

void bind_hermite(py::module_& m) {
  using Hermite = PythonOperator<HermiteCoons>;
  py::class_<Hermite>(m, "HermiteCoonsOperator", R"(C1 (Hermite) Coons interlineation, digest 001
§5.2: reproduces f and its normal derivative on every line.)")
      .def(
          "__call__",
          [](Hermite& O, const DoubleArray& x, const DoubleArray& y, int dx, int dy) {
            return evaluate_at(O, x, y, dx, dy, O.op.dim);
          },
          py::arg("x"), py::arg("y"), py::arg("dx") = 0, py::arg("dy") = 0, kEvaluateDoc)
      .def_property_readonly("dim", [](const Hermite& O) { return O.op.dim; });
  m.def(
      "hermite_coons",
      [](const VectorXd& x, const VectorXd& y, const std::vector<py::object>& on_x,
         const std::vector<py::object>& on_y, const std::vector<py::object>& dx_on_x,
         const std::vector<py::object>& dy_on_y, const MatrixXd& twists, double tolerance) {
        Hermite O;
        HermiteTraces t;
        t.values = line_traces(x, y, on_x, on_y, O.on_x_lines, O.on_y_lines);
        t.dx_on_x = traces_of(dx_on_x, O.on_x_lines);
        t.dy_on_y = traces_of(dy_on_y, O.on_y_lines);
        t.twists = twists;
        O.op = coons_hermite(t, tolerance);
        return O;
      },
      py::arg("x"), py::arg("y"), py::arg("on_x"), py::arg("on_y"), py::arg("dx_on_x"),
      py::arg("dy_on_y"), py::arg("twists") = MatrixXd(), py::arg("tolerance") = 1e-10,
      (std::string(R"(C1 Hermite Coons operator on the grid of lines x, y (>= 2 each).
dx_on_x[i]  t(s, d) = d^d/ds^d f_x(x[i], s), the normal derivative on the line x = x[i]
dy_on_y[j]  t(s, d) = d^d/ds^d f_y(s, y[j])
twists      optional (#x * #y, dim) f_xy at the crossings (row i + #x * j); default: from the
            traces.)") +
       kTracesDoc)
          .c_str());
}

void bind_cardinal(py::module_& m) {
  py::class_<CardinalSplines>(m, "CardinalSplines", R"(Cardinal blending functions
alpha_i(x_k) = delta_ik (digest 001 §5.1). Call it: alpha(x, nderiv=0) -> (nderiv + 1, n).)")
      .def_readonly("nodes", &CardinalSplines::nodes)
      .def_readonly("curve", &CardinalSplines::curve)
      .def_readonly("periodic", &CardinalSplines::periodic)
      .def(
          "__call__",
          [](const CardinalSplines& c, double x, int nderiv) { return evaluate(c, x, nderiv); },
          py::arg("x"), py::arg("nderiv") = 0);
  m.def("cardinal_splines", &cardinal_splines, py::arg("nodes"), py::arg("degree"),
        "Open cardinal splines of degree min(degree, n - 1) on n increasing nodes.");
  m.def("periodic_cardinal_splines", &periodic_cardinal_splines, py::arg("nodes"), py::arg("begin"),
        py::arg("period"), py::arg("degree"),
        "Periodic cardinal splines (degree 1 or 3) with period `period` from `begin`.");
}

} // namespace

void bind_interlineation(py::module_& m) {
  bind_gordon(m);
  bind_hermite(m);
  bind_cardinal(m);
}

} // namespace interlin::python
