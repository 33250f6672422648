// Point-cloud implicits <-> .ifl blocks of kinds cloud_pu and cloud_hrbf (cloud_implicit_ifl.h).
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"

#include "interlin/interflatation/models/ifl_codecs.h"
#include "interlin/interflatation/models/ifl_registry.h"

#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace interlin {

namespace {

// Per sheet: origin (3), frame rows (9), height coefficients (6).
constexpr long kSheetDoubles = 18;
// A stored frame is orthonormal to this tolerance (17 significant digits are written, so a
// fitted frame comes back exactly; the tolerance only rejects foreign data).
constexpr double kFrameTolerance = 1e-9;

void put_sheet(const HeightSheet& s, double* out) {
  for (int a = 0; a < 3; ++a)
    out[a] = s.origin(a);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[3 + 3 * r + c] = s.frame(r, c);
  for (int k = 0; k < 6; ++k)
    out[12 + k] = s.c[static_cast<size_t>(k)];
}

HeightSheet get_sheet(const double* in) {
  HeightSheet s;
  for (int a = 0; a < 3; ++a)
    s.origin(a) = in[a];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      s.frame(r, c) = in[3 + 3 * r + c];
  for (int k = 0; k < 6; ++k)
    s.c[static_cast<size_t>(k)] = in[12 + k];
  return s;
}

// #P by 3 matrices as the .ifl arrays store them (row-major).
using RowMajorX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

std::vector<double> row_major(const Eigen::MatrixX3d& A) {
  const RowMajorX3 R = A;
  return std::vector<double>(R.data(), R.data() + R.size());
}

void require_finite(const IflBlock& b, const std::string& name, const std::vector<double>& v) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      b.fail("array '" + name + "': value " + std::to_string(i) + " is not finite");
}

} // namespace

IflBlock to_ifl(const CloudImplicit& m, double noise) {
  const long n = static_cast<long>(m.fits.size());
  std::vector<std::int64_t> level, cell, sheets, conj;
  std::vector<double> centre, radius, sheet(static_cast<size_t>(n * 2 * kSheetDoubles));
  for (long i = 0; i < n; ++i) {
    const LocalFit& f = m.fits[static_cast<size_t>(i)];
    level.push_back(f.level);
    for (int a = 0; a < 3; ++a) {
      cell.push_back(f.cell(a));
      centre.push_back(f.centre(a));
    }
    radius.push_back(f.radius);
    sheets.push_back(f.sheets);
    conj.push_back(f.conjunction ? 1 : 0);
    for (size_t s = 0; s < 2; ++s)
      put_sheet(f.sheet[s], sheet.data() + (2 * i + long(s)) * kSheetDoubles);
  }
  IflBlock b;
  b.kind = "cloud_pu";
  b.name = "model";
  b.set("version", 1);
  set_box(b, "box", m.box);
  b.set_f64("origin", {3}, {m.origin(0), m.origin(1), m.origin(2)});
  b.set("size", m.size);
  b.set("support", m.support);
  b.set("noise", noise);
  b.set("spacing", m.spacing);
  b.set_i64("level", {n}, std::move(level));
  b.set_i64("cell", {n, 3}, std::move(cell));
  b.set_f64("centre", {n, 3}, std::move(centre));
  b.set_f64("radius", {n}, std::move(radius));
  b.set_i64("sheets", {n}, std::move(sheets));
  b.set_i64("conjunction", {n}, std::move(conj));
  b.set_f64("sheet", {n, 2, kSheetDoubles}, std::move(sheet));
  return b;
}

CloudImplicit cloud_implicit_from_ifl(const IflBlock& b) {
  b.expect("cloud_pu", 1);
  CloudImplicit m;
  m.box = box_from_block(b, "box");
  const std::vector<double>& o = b.f64("origin", {3});
  m.origin = Eigen::Vector3d(o[0], o[1], o[2]);
  m.size = b.number("size");
  m.support = b.number("support");
  if (!(m.size > 0) || !(m.support > 0.5))
    b.fail("needs size > 0 and support > 0.5");
  // optional (files before session 11 lack it): the fitted cloud's point spacing
  if (b.numbers.count("spacing")) {
    m.spacing = b.number("spacing");
    if (!(m.spacing >= 0))
      b.fail("needs spacing >= 0");
  }
  const std::vector<std::int64_t>& level = b.i64("level", {-1});
  const long n = static_cast<long>(level.size());
  if (n < 1)
    b.fail("array 'level': no leaves");
  const std::vector<std::int64_t>& cell = b.i64("cell", {n, 3});
  const std::vector<double>& centre = b.f64("centre", {n, 3});
  const std::vector<double>& radius = b.f64("radius", {n});
  const std::vector<std::int64_t>& sheets = b.i64("sheets", {n});
  const std::vector<std::int64_t>& conj = b.i64("conjunction", {n});
  const std::vector<double>& sheet = b.f64("sheet", {n, 2, kSheetDoubles});
  require_finite(b, "origin", o);
  require_finite(b, "centre", centre);
  require_finite(b, "radius", radius);
  require_finite(b, "sheet", sheet);
  m.fits.resize(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    LocalFit& f = m.fits[static_cast<size_t>(i)];
    const size_t k = static_cast<size_t>(i);
    if (level[k] < 0 || level[k] > 30)
      b.fail("leaf " + std::to_string(i) + ": level must be from 0 to 30");
    if (sheets[k] != 1 && sheets[k] != 2)
      b.fail("leaf " + std::to_string(i) + ": sheets must be 1 or 2");
    if (conj[k] != 0 && conj[k] != 1)
      b.fail("leaf " + std::to_string(i) + ": conjunction must be 0 or 1");
    f.level = static_cast<int>(level[k]);
    for (int a = 0; a < 3; ++a) {
      const std::int64_t c = cell[3 * k + size_t(a)];
      if (c < 0 || c >= (std::int64_t{1} << f.level))
        b.fail("leaf " + std::to_string(i) + ": cell index outside its level's grid");
      f.cell(a) = static_cast<int>(c);
      f.centre(a) = centre[3 * k + size_t(a)];
    }
    f.radius = radius[k];
    f.sheets = static_cast<int>(sheets[k]);
    f.conjunction = conj[k] == 1;
    for (size_t s = 0; s < 2; ++s) {
      f.sheet[s] = get_sheet(sheet.data() + (2 * i + long(s)) * kSheetDoubles);
      const Eigen::Matrix3d& F = f.sheet[s].frame;
      if ((F * F.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > kFrameTolerance)
        b.fail("leaf " + std::to_string(i) + ": a sheet's frame is not orthonormal");
    }
  }
  return m;
}

IflBlock to_ifl(const HermiteRbf& m) {
  const long n = static_cast<long>(m.points.rows());
  IflBlock b;
  b.kind = "cloud_hrbf";
  b.name = "model";
  b.set("version", 1);
  set_box(b, "box", m.box);
  b.set_f64("centre", {3}, {m.centre(0), m.centre(1), m.centre(2)});
  b.set("scale", m.scale);
  b.set("spacing", m.spacing);
  b.set_f64("points", {n, 3}, row_major(m.points));
  b.set_f64("a", {n}, std::vector<double>(m.a.data(), m.a.data() + n));
  b.set_f64("b", {n, 3}, row_major(m.b));
  b.set_f64("linear", {4}, {m.c, m.g(0), m.g(1), m.g(2)});
  return b;
}

HermiteRbf hermite_rbf_from_ifl(const IflBlock& b) {
  b.expect("cloud_hrbf", 1);
  HermiteRbf m;
  m.box = box_from_block(b, "box");
  const std::vector<double>& c = b.f64("centre", {3});
  m.scale = b.number("scale");
  m.spacing = b.number("spacing");
  if (!(m.scale > 0) || !(m.spacing >= 0))
    b.fail("needs scale > 0 and spacing >= 0");
  const std::vector<double>& a = b.f64("a", {-1});
  const long n = static_cast<long>(a.size());
  if (n < 4)
    b.fail("array 'a': fewer than 4 centres");
  const std::vector<double>& p = b.f64("points", {n, 3});
  const std::vector<double>& beta = b.f64("b", {n, 3});
  const std::vector<double>& lin = b.f64("linear", {4});
  for (const auto& [name, v] :
       {std::pair{"centre", &c}, {"points", &p}, {"a", &a}, {"b", &beta}, {"linear", &lin}})
    require_finite(b, name, *v);
  m.centre = Eigen::Vector3d(c[0], c[1], c[2]);
  m.points = Eigen::Map<const RowMajorX3>(p.data(), n, 3);
  m.b = Eigen::Map<const RowMajorX3>(beta.data(), n, 3);
  m.a = Eigen::Map<const Eigen::VectorXd>(a.data(), n);
  m.c = lin[0];
  m.g = Eigen::Vector3d(lin[1], lin[2], lin[3]);
  return m;
}

void register_cloud_ifl_kind() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_ifl_kind("cloud_pu", [](const IflBlock& b, const std::string&) {
      auto m = std::make_shared<const CloudImplicit>(cloud_implicit_from_ifl(b));
      try {
        return cloud_implicit_function(m);
      } catch (const std::invalid_argument& e) {
        b.fail(e.what());
      }
    });
    register_ifl_kind("cloud_hrbf", [](const IflBlock& b, const std::string&) {
      return hermite_rbf_function(std::make_shared<const HermiteRbf>(hermite_rbf_from_ifl(b)));
    });
  });
}

} // namespace interlin
