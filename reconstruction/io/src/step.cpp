// STEP AP214 writer: B-spline face, or closed shell with cap faces (ISO 10303-21 clear text).
#include "interlin/reconstruction/io/step.h"

#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/splines/knot_insertion.h"

#include "cad_text.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

namespace {

// The DATA section under construction: entity instances numbered #1, #2, ... in order.
class Data {
public:
  int add(const std::string& text) {
    lines_.push_back(text);
    return int(lines_.size());
  }
  void write(std::ostream& out) const {
    for (size_t i = 0; i < lines_.size(); ++i)
      out << '#' << i + 1 << '=' << lines_[i] << ";\n";
  }

private:
  std::vector<std::string> lines_;
};

std::string ref(int id) {
  return "#" + std::to_string(id);
}

template <class T, class F>
std::string list(const std::vector<T>& items, F&& text) {
  std::string s = "(";
  for (size_t i = 0; i < items.size(); ++i)
    s += (i ? "," : "") + text(items[i]);
  return s + ")";
}

std::string refs(const std::vector<int>& ids) {
  return list(ids, ref);
}

std::string flag(bool b) {
  return b ? ".T." : ".F.";
}

// STEP strings: printable ASCII, the apostrophe doubled, backslash escaped as \\ (ISO 10303-21
// §6.4.3).
std::string str(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u > 0x7e)
      out += '?';
    else if (c == '\'')
      out += "''";
    else if (c == '\\')
      out += "\\\\";
    else
      out += c;
  }
  return out + "'";
}

std::string point_text(const Eigen::Vector3d& p) {
  return "(" + detail::cad_real(p(0)) + "," + detail::cad_real(p(1)) + "," +
         detail::cad_real(p(2)) + ")";
}

int cartesian_point(Data& d, const Eigen::Vector3d& p) {
  return d.add("CARTESIAN_POINT(''," + point_text(p) + ")");
}

// Distinct knot values and their multiplicities.
void knots_with_multiplicities(const Eigen::VectorXd& k, std::vector<double>& values,
                               std::vector<int>& mult) {
  values.clear();
  mult.clear();
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    if (!values.empty() && values.back() == k(i))
      ++mult.back();
    else
      values.push_back(k(i)), mult.push_back(1);
  }
}

// "(multiplicities)" and "(distinct values)" of a knot vector.
std::pair<std::string, std::string> knot_text(const Eigen::VectorXd& k) {
  std::vector<double> values;
  std::vector<int> mult;
  knots_with_multiplicities(k, values, mult);
  return {list(mult, [](int m) { return std::to_string(m); }),
          list(values, [](double x) { return detail::cad_real(x); })};
}

int bspline_curve(Data& d, const BSplineCurve& c, bool closed) {
  std::vector<int> pts;
  for (Eigen::Index i = 0; i < c.ctrl.rows(); ++i)
    pts.push_back(cartesian_point(d, c.ctrl.row(i).transpose()));
  const auto [mult, knots] = knot_text(c.knots);
  return d.add("B_SPLINE_CURVE_WITH_KNOTS(''," + std::to_string(c.degree) + "," + refs(pts) +
               ",.UNSPECIFIED.," + flag(closed) + ",.F.," + mult + "," + knots + ",.UNSPECIFIED.)");
}

int bspline_surface(Data& d, const BSplineSurface& s) {
  // control_points_list[i][j]: u index outer, v index inner.
  std::string rows = "(";
  for (Eigen::Index i = 0; i < s.num_u; ++i) {
    std::vector<int> pts;
    for (Eigen::Index j = 0; j < s.num_v; ++j)
      pts.push_back(cartesian_point(d, s.ctrl.row(i + s.num_u * j).transpose()));
    rows += (i ? "," : "") + refs(pts);
  }
  rows += ")";
  // Attribute order: multiplicities u, v, then knots u, v (ISO 10303-42).
  const auto [mu, ku] = knot_text(s.knots_u);
  const auto [mv, kv] = knot_text(s.knots_v);
  return d.add("B_SPLINE_SURFACE_WITH_KNOTS(''," + std::to_string(s.degree_u) + "," +
               std::to_string(s.degree_v) + "," + rows + ",.UNSPECIFIED.," + flag(false) +
               ",.F.,.F.," + mu + "," + mv + "," + ku + "," + kv + ",.UNSPECIFIED.)");
}

// The parameter lines of the surface as clamped curves: u = const (a column of the control net,
// v knots) or v = const at a domain end (a row, u knots).
BSplineCurve row_curve(const BSplineSurface& s, Eigen::Index j) {
  BSplineCurve c;
  c.degree = s.degree_u;
  c.knots = s.knots_u;
  c.ctrl = s.ctrl.middleRows(j * s.num_u, s.num_u);
  return c;
}

BSplineCurve column_curve(const BSplineSurface& s, Eigen::Index i) {
  BSplineCurve c;
  c.degree = s.degree_v;
  c.knots = s.knots_v;
  c.ctrl.resize(s.num_v, 3);
  for (Eigen::Index j = 0; j < s.num_v; ++j)
    c.ctrl.row(j) = s.ctrl.row(i + s.num_u * j);
  return c;
}

struct Edge {
  int id;
  int start, end; // vertex ids
};

int vertex(Data& d, const Eigen::Vector3d& p) {
  return d.add("VERTEX_POINT(''," + ref(cartesian_point(d, p)) + ")");
}

Edge edge(Data& d, const BSplineCurve& c, int start, int end, bool closed) {
  const int curve = bspline_curve(d, c, closed);
  return {d.add("EDGE_CURVE(''," + ref(start) + "," + ref(end) + "," + ref(curve) + ",.T.)"), start,
          end};
}

int oriented(Data& d, const Edge& e, bool forward) {
  return d.add("ORIENTED_EDGE('',*,*," + ref(e.id) + "," + flag(forward) + ")");
}

int face(Data& d, const std::vector<int>& oriented_edges, int surface, bool same_sense,
         bool bound_forward) {
  const int loop = d.add("EDGE_LOOP(''," + refs(oriented_edges) + ")");
  const int bound = d.add("FACE_OUTER_BOUND(''," + ref(loop) + "," + flag(bound_forward) + ")");
  return d.add("ADVANCED_FACE(''," + refs({bound}) + "," + ref(surface) + "," + flag(same_sense) +
               ")");
}

// The end loop at row j split at the sorted parameters `cuts` (u0 among them): its vertices and
// edges in increasing u; edge k runs from cuts[k] to cuts[k + 1] (the last one to u1).
std::vector<Edge> loop_edges(Data& d, const BSplineSurface& s, Eigen::Index j,
                             const std::vector<double>& cuts, int& seam_vertex) {
  const BSplineCurve loop = row_curve(s, j);
  std::vector<Edge> edges;
  if (cuts.size() == 1) {
    seam_vertex = vertex(d, loop.ctrl.row(0).transpose());
    edges.push_back(edge(d, loop, seam_vertex, seam_vertex, true));
    return edges;
  }
  const double u1 = loop.knots(loop.ctrl.rows());
  std::vector<BSplineCurve> pieces;
  std::vector<int> v;
  for (size_t k = 0; k < cuts.size(); ++k) {
    pieces.push_back(curve_piece(loop, cuts[k], k + 1 < cuts.size() ? cuts[k + 1] : u1));
    v.push_back(vertex(d, pieces.back().ctrl.row(0).transpose()));
  }
  seam_vertex = v[0];
  for (size_t k = 0; k < cuts.size(); ++k)
    edges.push_back(edge(d, pieces[k], v[k], v[(k + 1) % v.size()], false));
  return edges;
}

// sum over the loop at parameter v of (S_u x S_v) . (S - centroid): positive when S_u x S_v points
// out of the tube (2 x the section's area x |S_v| on a planar section).
double outward_sign(const PiecewiseSurface& ps, double u0, double u1, double v) {
  constexpr int kSamples = 256;
  std::vector<Eigen::Vector3d> p, n;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < kSamples; ++i) {
    const double u = u0 + (u1 - u0) * i / kSamples;
    p.push_back(evaluate(ps, u, v));
    n.push_back(evaluate(ps, u, v, 1, 0).cross(evaluate(ps, u, v, 0, 1)));
    c += p.back() / kSamples;
  }
  double sum = 0;
  for (int i = 0; i < kSamples; ++i)
    sum += n[size_t(i)].dot(p[size_t(i)] - c);
  return sum;
}

// Length unit entities; returns the unit's id.
int length_unit(Data& d, LengthUnit unit) {
  switch (unit) {
  case LengthUnit::mm:
    return d.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))");
  case LengthUnit::cm:
    return d.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.CENTI.,.METRE.))");
  case LengthUnit::m:
    return d.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.))");
  case LengthUnit::inch: {
    const int mm = d.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))");
    const int measure = d.add("LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4)," + ref(mm) + ")");
    const int dims = d.add("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)");
    return d.add("(CONVERSION_BASED_UNIT('INCH'," + ref(measure) + ")LENGTH_UNIT()NAMED_UNIT(" +
                 ref(dims) + "))");
  }
  }
  throw std::invalid_argument("write_step: unknown LengthUnit");
}

} // namespace

void write_step(const std::string& path, const BSplineSurface& s,
                const std::array<StepCap, 2>* caps, const StepOptions& opt) {
  check_surface(s);
  const double u0 = s.knots_u(s.degree_u), u1 = s.knots_u(s.num_u);
  const double v0 = s.knots_v(s.degree_v), v1 = s.knots_v(s.num_v);
  if (caps) {
    if (!s.closed_u)
      throw std::invalid_argument("write_step: caps need a surface closed around (closed_u)");
    for (const StepCap& c : *caps) {
      check_surface(c.patch);
      for (double u : c.corner_u)
        if (!(u >= u0 && u < u1))
          throw std::invalid_argument("write_step: cap corner outside the surface's u domain");
      if (!(c.corner_u[0] < c.corner_u[1]))
        throw std::invalid_argument("write_step: cap corners must increase");
    }
  }
  if (!(opt.relative_uncertainty > 0))
    throw std::invalid_argument("write_step: relative_uncertainty must be > 0");
  Data d;
  // Product structure (AP214 CC2).
  const int app = d.add("APPLICATION_CONTEXT('automotive design')");
  d.add("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000," +
        ref(app) + ")");
  const int pc = d.add("PRODUCT_CONTEXT(''," + ref(app) + ",'mechanical')");
  const int product =
      d.add("PRODUCT(" + str(opt.name) + "," + str(opt.name) + ",''," + refs({pc}) + ")");
  d.add("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$," + refs({product}) + ")");
  const int pdf = d.add("PRODUCT_DEFINITION_FORMATION('',''," + ref(product) + ")");
  const int pdc = d.add("PRODUCT_DEFINITION_CONTEXT('part definition'," + ref(app) + ",'design')");
  const int pd = d.add("PRODUCT_DEFINITION('design',''," + ref(pdf) + "," + ref(pdc) + ")");
  const int pds = d.add("PRODUCT_DEFINITION_SHAPE('',''," + ref(pd) + ")");
  // Units and the geometric context.
  const int length = length_unit(d, opt.unit);
  const int angle = d.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))");
  const int solid_angle = d.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())");
  const Eigen::Vector3d lo = s.ctrl.colwise().minCoeff(), hi = s.ctrl.colwise().maxCoeff();
  const double uncertainty = opt.relative_uncertainty * std::max((hi - lo).norm(), 1e-300);
  const int unc =
      d.add("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(" + detail::cad_real(uncertainty) + ")," +
            ref(length) + ",'distance_accuracy_value','confusion accuracy')");
  const int ctx =
      d.add("(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT(" +
            refs({unc}) + ")GLOBAL_UNIT_ASSIGNED_CONTEXT(" + refs({length, angle, solid_angle}) +
            ")REPRESENTATION_CONTEXT('3D','3D context with units and uncertainty'))");
  const int origin = cartesian_point(d, Eigen::Vector3d::Zero());
  const int axis =
      d.add("AXIS2_PLACEMENT_3D(''," + ref(origin) + "," + ref(d.add("DIRECTION('',(0.,0.,1.))")) +
            "," + ref(d.add("DIRECTION('',(1.,0.,0.))")) + ")");

  // Lateral face: the end loops (split at the caps' corners), the seam or the two sides.
  const int lateral = bspline_surface(d, s);
  std::vector<int> faces;
  bool outward = true;
  if (s.closed_u) {
    const PiecewiseSurface ps = to_piecewise(s);
    outward = outward_sign(ps, u0, u1, 0.5 * (v0 + v1)) >= 0;
    std::vector<double> cuts0 = {u0}, cuts1 = {u0};
    if (caps) {
      cuts0.insert(cuts0.end(), (*caps)[0].corner_u.begin(), (*caps)[0].corner_u.end());
      cuts1.insert(cuts1.end(), (*caps)[1].corner_u.begin(), (*caps)[1].corner_u.end());
      for (auto* c : {&cuts0, &cuts1})
        c->erase(std::unique(c->begin(), c->end()), c->end());
    }
    int a = 0, b = 0;
    const std::vector<Edge> bottom = loop_edges(d, s, 0, cuts0, a);
    const std::vector<Edge> top = loop_edges(d, s, s.num_v - 1, cuts1, b);
    const Edge seam = edge(d, column_curve(s, 0), a, b, false);
    // Counter-clockwise in the parameter plane: bottom +u, seam up (at u1), top -u, seam down.
    std::vector<int> loop;
    for (const Edge& e : bottom)
      loop.push_back(oriented(d, e, true));
    loop.push_back(oriented(d, seam, true));
    for (auto e = top.rbegin(); e != top.rend(); ++e)
      loop.push_back(oriented(d, *e, false));
    loop.push_back(oriented(d, seam, false));
    faces.push_back(face(d, loop, lateral, outward, outward));
    if (caps) {
      // Each cap uses its loop's edges against the lateral face's effective direction
      // (outward: the lateral face runs the bottom loop +u and the top loop -u).
      const std::vector<Edge>* loops[2] = {&bottom, &top};
      for (int k = 0; k < 2; ++k) {
        const StepCap& c = (*caps)[size_t(k)];
        const bool plus_u = (k == 0) != outward; // direction the cap runs its loop
        std::vector<int> cap_loop;
        if (plus_u)
          for (const Edge& e : *loops[k])
            cap_loop.push_back(oriented(d, e, true));
        else
          for (auto e = loops[k]->rbegin(); e != loops[k]->rend(); ++e)
            cap_loop.push_back(oriented(d, *e, false));
        // The patch's parameter-plane boundary runs the loop +u counter-clockwise around
        // P_s x P_t: the cap's normal is that one exactly when it runs its loop +u.
        faces.push_back(face(d, cap_loop, bspline_surface(d, c.patch), plus_u, true));
      }
    }
  } else {
    const Eigen::Index nu = s.num_u, nv = s.num_v;
    const int c00 = vertex(d, s.ctrl.row(0).transpose()),
              c10 = vertex(d, s.ctrl.row(nu - 1).transpose()),
              c01 = vertex(d, s.ctrl.row(nu * (nv - 1)).transpose()),
              c11 = vertex(d, s.ctrl.row(nu * nv - 1).transpose());
    const Edge e0 = edge(d, row_curve(s, 0), c00, c10, false);
    const Edge e1 = edge(d, column_curve(s, nu - 1), c10, c11, false);
    const Edge e2 = edge(d, row_curve(s, nv - 1), c01, c11, false);
    const Edge e3 = edge(d, column_curve(s, 0), c00, c01, false);
    faces.push_back(face(d,
                         {oriented(d, e0, true), oriented(d, e1, true), oriented(d, e2, false),
                          oriented(d, e3, false)},
                         lateral, true, true));
  }
  int rep = 0;
  if (caps) {
    const int shell = d.add("CLOSED_SHELL(''," + refs(faces) + ")");
    const int solid = d.add("MANIFOLD_SOLID_BREP(" + str(opt.name) + "," + ref(shell) + ")");
    rep = d.add("ADVANCED_BREP_SHAPE_REPRESENTATION(" + str(opt.name) + "," + refs({axis, solid}) +
                "," + ref(ctx) + ")");
  } else {
    const int shell = d.add("OPEN_SHELL(''," + refs(faces) + ")");
    const int model =
        d.add("SHELL_BASED_SURFACE_MODEL(" + str(opt.name) + "," + refs({shell}) + ")");
    rep = d.add("MANIFOLD_SURFACE_SHAPE_REPRESENTATION(" + str(opt.name) + "," +
                refs({axis, model}) + "," + ref(ctx) + ")");
  }
  d.add("SHAPE_DEFINITION_REPRESENTATION(" + ref(pds) + "," + ref(rep) + ")");

  const std::string file = std::filesystem::path(path).filename().string();
  write_file_atomically(path, [&](std::ostream& out) {
    out << "ISO-10303-21;\nHEADER;\n"
        << "FILE_DESCRIPTION((" << str(opt.description) << "),'2;1');\n"
        << "FILE_NAME(" << str(file) << "," << str(detail::file_time("%Y-%m-%dT%H:%M:%S"))
        << ",(''),(''),'interlin','interlin','');\n"
        << "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
    d.write(out);
    out << "ENDSEC;\nEND-ISO-10303-21;\n";
  });
}

} // namespace interlin
