// Python bindings of splines/ (seed 004): natural-parametrization curves and their fits, axial
// cascade profiles and their span stacking, Frenet space curves.
#include "bindings.h"

#include "interlin/splines/cascade_profile.h"
#include "interlin/splines/cascade_stack.h"
#include "interlin/splines/frenet_curve.h"
#include "interlin/splines/natural_curve.h"
#include "interlin/splines/natural_fit.h"

#include <tuple>
#include <vector>

namespace interlin::python {

namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;

QuadratureOptions quadrature(const std::string& rule, double tolerance, int intervals) {
  const NaturalQuadrature r =
      choice<NaturalQuadrature>({{"adaptive", NaturalQuadrature::adaptive_gauss},
                                 {"trapezoid", NaturalQuadrature::trapezoid}},
                                rule, "rule");
  return {r, tolerance, intervals};
}

ShootingOptions shooting(bool book) {
  return book ? book_mode() : ShootingOptions{};
}

void bind_natural(py::module_& m) {
  py::class_<CurvatureLaw>(m, "CurvatureLaw",
                           R"(k(s) = sum_j poly[j] s^j + sum_m a_m sin(f_m s + p_m)
(seed 004 §1.3-1.4). waves: list of (amplitude, frequency, phase).)")
      .def(py::init([](VectorXd poly, const std::vector<std::tuple<double, double, double>>& w) {
             CurvatureLaw k{std::move(poly), {}};
             for (const auto& [a, f, p] : w)
               k.waves.push_back({a, f, p});
             return k;
           }),
           py::arg("poly"), py::arg("waves") = std::vector<std::tuple<double, double, double>>{})
      .def_readonly("poly", &CurvatureLaw::poly)
      .def(
          "__call__",
          [](const CurvatureLaw& k, const DoubleArray& s, int deriv) {
            return map_elements(s, [&](double t) { return curvature(k, t, deriv); });
          },
          py::arg("s"), py::arg("deriv") = 0, "k^(deriv)(s), elementwise.")
      .def(
          "turning",
          [](const CurvatureLaw& k, const DoubleArray& s) {
            return map_elements(s, [&](double t) { return turning(k, t); });
          },
          py::arg("s"), "int_0^s k(t) dt in closed form (seed 004 (1.3)), elementwise.");
  m.def("polynomial_law", &polynomial_law, py::arg("c"), "k(s) = sum_j c[j] s^j.");
  m.def("sine_law", &sine_law, py::arg("a"), py::arg("b"), py::arg("c"),
        "seed 004 (1.5): k = a sin(b s) + c.");
  m.def("sine_squared_law", &sine_squared_law, py::arg("A"), py::arg("b"),
        "seed 004 (1.6): k = A sin^2(b s) + 1.");

  py::class_<PlanarNaturalCurve>(m, "NaturalCurve", R"(Planar curve from its curvature law
(seed 004 (1.3)-(1.4)): start point (2,), start tangent angle phi0 (radians), law, length.)")
      .def(py::init([](const Vector2d& start, double phi0, CurvatureLaw law, double length) {
             return PlanarNaturalCurve{start, phi0, std::move(law), length};
           }),
           py::arg("start"), py::arg("phi0"), py::arg("law"), py::arg("length"))
      .def_readonly("start", &PlanarNaturalCurve::start)
      .def_readonly("phi0", &PlanarNaturalCurve::phi0)
      .def_readonly("law", &PlanarNaturalCurve::law)
      .def_readonly("length", &PlanarNaturalCurve::length)
      .def(
          "sample",
          [](const PlanarNaturalCurve& c, const VectorXd& s, const std::string& rule,
             double tolerance, int intervals) {
            NaturalSamples n = sample_natural_curve(c, s, quadrature(rule, tolerance, intervals));
            py::dict d;
            d["s"] = std::move(n.s);
            d["points"] = std::move(n.points);
            d["phi"] = std::move(n.phi);
            d["k"] = std::move(n.k);
            d["dk"] = std::move(n.dk);
            return d;
          },
          py::arg("s"), py::arg("rule") = "adaptive", py::arg("tolerance") = 1e-14,
          py::arg("intervals") = 2000,
          R"(Points and curvature-plot data at increasing arc lengths s (#s,): dict with s,
points (#s, 2), phi, k, dk (#s,). rule "adaptive" (Gauss-Legendre, ~1e-14) or "trapezoid"
(the book's rule with `intervals` panels).)");

  py::class_<CurvePose>(m, "CurvePose", "A point (2,) with a tangent angle (radians).")
      .def(py::init([](const Vector2d& p, double angle) {
             return CurvePose{p, angle};
           }),
           py::arg("point"), py::arg("angle"))
      .def_readonly("point", &CurvePose::point)
      .def_readonly("angle", &CurvePose::angle);
  py::class_<NaturalFit>(m, "NaturalFit", "Fitted pieces (NaturalCurve) and the largest miss.")
      .def_readonly("pieces", &NaturalFit::pieces)
      .def_readonly("miss", &NaturalFit::miss);
  m.def(
      "fit_hermite_curvature",
      [](const CurvePose& p0, const CurvePose& p1, const VectorXd& fixed, bool book) {
        return fit_hermite_curvature(p0, p1, fixed, shooting(book));
      },
      py::arg("p0"), py::arg("p1"), py::arg("fixed") = VectorXd(), py::arg("book_mode") = false,
      R"(seed 004 (1.7)-(1.11), §4.1-4.2: G1 Hermite arc p0 -> p1 whose curvature polynomial has the
lower coefficients `fixed` (m = 0: clothoid, 1: quadratic, 2: cubic segment). book_mode: the
book's Hooke-Jeeves + trapezoid setting (miss <= 1e-4).)");
  m.def(
      "fit_linear_curvature_chain",
      [](const std::vector<CurvePose>& poses, bool book) {
        return fit_linear_curvature_chain(poses, shooting(book));
      },
      py::arg("poses"), py::arg("book_mode") = false,
      "seed 004 §1.6: composite clothoid through the poses (G1 at the nodes).");
}

void bind_cascade(py::module_& m) {
  py::class_<CascadeParameters>(m, "CascadeParameters", R"(The 13 parameters of an axial-turbine
cascade profile (seed 004 §4.1): lengths in any unit, angles in degrees. Keyword arguments:
relative_pitch, axial_width, stagger_deg, inlet_angle_deg, outlet_angle_deg, le_wedge_deg,
te_wedge_deg, le_radius, te_radius, te_bend_deg, max_thickness_position, max_thickness, throat.)")
      .def(py::init([](py::kwargs kw) {
        CascadeParameters p;
        const std::map<std::string, double*> fields = {
            {"relative_pitch", &p.relative_pitch},
            {"axial_width", &p.axial_width},
            {"stagger_deg", &p.stagger_deg},
            {"inlet_angle_deg", &p.inlet_angle_deg},
            {"outlet_angle_deg", &p.outlet_angle_deg},
            {"le_wedge_deg", &p.le_wedge_deg},
            {"te_wedge_deg", &p.te_wedge_deg},
            {"le_radius", &p.le_radius},
            {"te_radius", &p.te_radius},
            {"te_bend_deg", &p.te_bend_deg},
            {"max_thickness_position", &p.max_thickness_position},
            {"max_thickness", &p.max_thickness},
            {"throat", &p.throat}};
        for (const auto& [key, value] : kw) {
          const auto it = fields.find(key.cast<std::string>());
          if (it == fields.end())
            throw py::type_error("CascadeParameters: unknown parameter '" +
                                 key.cast<std::string>() + "'");
          *it->second = value.cast<double>();
        }
        return p;
      }))
      .def_readwrite("relative_pitch", &CascadeParameters::relative_pitch)
      .def_readwrite("axial_width", &CascadeParameters::axial_width)
      .def_readwrite("stagger_deg", &CascadeParameters::stagger_deg)
      .def_readwrite("inlet_angle_deg", &CascadeParameters::inlet_angle_deg)
      .def_readwrite("outlet_angle_deg", &CascadeParameters::outlet_angle_deg)
      .def_readwrite("le_wedge_deg", &CascadeParameters::le_wedge_deg)
      .def_readwrite("te_wedge_deg", &CascadeParameters::te_wedge_deg)
      .def_readwrite("le_radius", &CascadeParameters::le_radius)
      .def_readwrite("te_radius", &CascadeParameters::te_radius)
      .def_readwrite("te_bend_deg", &CascadeParameters::te_bend_deg)
      .def_readwrite("max_thickness_position", &CascadeParameters::max_thickness_position)
      .def_readwrite("max_thickness", &CascadeParameters::max_thickness)
      .def_readwrite("throat", &CascadeParameters::throat);

  py::class_<CascadeProfile>(m, "CascadeProfile", R"(Result of cascade_profile.

Attributes: points (P, 2) closed profile (first point not repeated, from the trailing-edge
middle towards the suction side); pitch, throat, max_thickness (absolute); O1, O2 edge circle
centres; suction, pressure (lists of NaturalCurve); miss (largest end-point miss).)")
      .def_readonly("points", &CascadeProfile::points)
      .def_readonly("pitch", &CascadeProfile::pitch)
      .def_readonly("throat", &CascadeProfile::throat)
      .def_readonly("max_thickness", &CascadeProfile::max_thickness)
      .def_readonly("O1", &CascadeProfile::O1)
      .def_readonly("O2", &CascadeProfile::O2)
      .def_readonly("suction", &CascadeProfile::suction)
      .def_readonly("pressure", &CascadeProfile::pressure)
      .def_readonly("miss", &CascadeProfile::miss);

  const auto options = [](const std::string& joint, int side, int edge) {
    CascadeOptions o;
    o.joint = choice<CascadeJoint>(
        {{"g2", CascadeJoint::g2_quadratic}, {"g3", CascadeJoint::g3_cubic}}, joint, "joint");
    o.side_intervals = side;
    o.edge_intervals = edge;
    return o;
  };
  m.def(
      "cascade_profile",
      [options](const CascadeParameters& p, const std::string& joint, int side, int edge) {
        return cascade_profile(p, options(joint, side, edge));
      },
      py::arg("parameters"), py::arg("joint") = "g3", py::arg("side_intervals") = 60,
      py::arg("edge_intervals") = 16,
      "seed 004 §4.1-4.2: the cascade profile of 13 parameters; joint 'g3' (cubic curvature, "
      "default) or 'g2' (quadratic). ValueError for the book's non-constructive profiles.");
  m.def(
      "side_curvature_plot",
      [](const std::vector<PlanarNaturalCurve>& side, int samples) {
        return side_curvature_plot(side, samples);
      },
      py::arg("side"), py::arg("samples") = 200,
      "Curvature plot of one side: (samples, 7) with columns sbar, s, x, y, phi, k, k'.");
  m.def(
      "stack_cascade_profiles",
      [options](const std::vector<std::pair<double, CascadeParameters>>& stations,
                const std::string& align, const std::string& joint, int side, int edge) {
        std::vector<SpanStation> s;
        for (const auto& [radius, p] : stations)
          s.push_back({radius, p});
        const StackAlign a = choice<StackAlign>({{"centroid", StackAlign::centroid},
                                                 {"le", StackAlign::leading_edge},
                                                 {"te", StackAlign::trailing_edge},
                                                 {"none", StackAlign::none}},
                                                align, "align");
        return stack_cascade_profiles(s, a, options(joint, side, edge));
      },
      py::arg("stations"), py::arg("align") = "centroid", py::arg("joint") = "g3",
      py::arg("side_intervals") = 60, py::arg("edge_intervals") = 16,
      R"(One profile per (radius, CascadeParameters) station in the plane z = radius, aligned on
the stacking line: a list of (P, 3) sections with equal P (the loft's input).)");
}

void bind_frenet(py::module_& m) {
  m.def(
      "integrate_frenet",
      [](const VectorXd& k_s, const VectorXd& k, const VectorXd& tau_s, const VectorXd& tau,
         const VectorXd& s, const std::string& method, double step, double tolerance) {
        FrenetOptions o;
        o.method = choice<FrenetIntegrator>(
            {{"rk4", FrenetIntegrator::rk4}, {"adaptive", FrenetIntegrator::adaptive}}, method,
            "method");
        o.step = step;
        o.tolerance = tolerance;
        const std::vector<FrenetFrame> f = integrate_frenet({k_s, k}, {tau_s, tau}, s, {}, o);
        MatrixXd r(s.size(), 3), t(s.size(), 3), n(s.size(), 3), b(s.size(), 3);
        for (size_t i = 0; i < f.size(); ++i) {
          r.row(Eigen::Index(i)) = f[i].r;
          t.row(Eigen::Index(i)) = f[i].t;
          n.row(Eigen::Index(i)) = f[i].n;
          b.row(Eigen::Index(i)) = f[i].b;
        }
        return py::make_tuple(std::move(r), std::move(t), std::move(n), std::move(b));
      },
      py::arg("k_s"), py::arg("k"), py::arg("tau_s"), py::arg("tau"), py::arg("s"),
      py::arg("method") = "adaptive", py::arg("step") = 1e-2, py::arg("tolerance") = 1e-12,
      R"(seed 004 §2.4: space curve from piecewise-linear curvature (k_s, k) and torsion
(tau_s, tau) laws, frames at arc lengths s (#s,) from the origin with t = e_x, n = e_y.
Returns (r, t, n, b), each (#s, 3).)");
}

} // namespace

void bind_curves(py::module_& m) {
  bind_natural(m);
  bind_cascade(m);
  bind_frenet(m);
}

} // namespace interlin::python
