#include "interlin/reconstruction/io/preview.h"

#include "interlin/reconstruction/io/atomic_file.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <png.h>
#include <stdexcept>

namespace interlin {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFill = 0.85;     // fraction of the frame the fitted object spans
constexpr double kLineWidth = 1.5; // polyline width in output pixels
constexpr long long kMaxSubpixels = 1LL << 26;

// Colours in display space, [0, 1].
const Eigen::Vector3d kBase(0.55, 0.62, 0.72); // metallic blue-grey
const Eigen::Vector3d kLine(0.10, 0.12, 0.16); // section curves

void fail(const std::string& what) {
  throw std::invalid_argument("render_preview: " + what);
}

void check_inputs(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                  const std::vector<Eigen::MatrixXd>& polylines, const PreviewOptions& o) {
  if (V.rows() == 0 || F.rows() == 0)
    fail("empty mesh");
  if (V.cols() != 3 || F.cols() != 3)
    fail("V and F must have 3 columns");
  if (!V.allFinite())
    fail("non-finite vertex coordinates");
  if (F.minCoeff() < 0 || F.maxCoeff() >= V.rows())
    fail("face index out of range");
  for (const auto& P : polylines) {
    if (P.rows() == 0)
      continue;
    if (P.cols() != 3)
      fail("polylines must have 3 columns");
    if (!P.allFinite())
      fail("non-finite polyline coordinates");
  }
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    fail("image size out of range");
  if (o.supersample < 1 || o.supersample > 8)
    fail("supersample must be in [1, 8]");
  const long long k = o.supersample;
  if (static_cast<long long>(o.width) * o.height * k * k > kMaxSubpixels)
    fail("width * height * supersample^2 exceeds 2^26");
  if (!std::isfinite(o.azimuth_deg) || !std::isfinite(o.elevation_deg))
    fail("non-finite view angles");
  if (!o.up.allFinite())
    fail("non-finite up vector");
  if (!o.background_top.allFinite() || !o.background_bottom.allFinite())
    fail("non-finite background colour");
}

// v with its largest-magnitude component made positive (the first one on ties).
Eigen::Vector3d canonical_sign(const Eigen::Vector3d& v) {
  Eigen::Index imax = 0;
  v.cwiseAbs().maxCoeff(&imax);
  return v(imax) < 0 ? Eigen::Vector3d(-v) : v;
}

// Unit eigenvector of the symmetric C for its largest eigenvalue, or the zero vector when that
// eigenvalue is not separated from the next one (no preferred direction).
Eigen::Vector3d dominant_axis(const Eigen::Matrix3d& C) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  const Eigen::Vector3d lambda = es.eigenvalues(); // ascending
  if (!(lambda(2) > 0) || lambda(2) - lambda(1) <= 1e-6 * lambda(2))
    return Eigen::Vector3d::Zero();
  return canonical_sign(es.eigenvectors().col(2).normalized());
}

// Orthonormal camera frame: right x up = toward (from the scene to the camera).
struct Camera {
  Eigen::Vector3d right, up, toward;
};

// The camera of the 3/4 view. Vertical: `up`, or the largest principal axis of V. Azimuth 0:
// the principal axis of V projected onto the plane orthogonal to the vertical (for a blade, the
// mean chord), or, without a clear one, the coordinate axis least aligned with the vertical.
Camera make_camera(const Eigen::MatrixXd& V, const PreviewOptions& o) {
  const Eigen::RowVector3d centroid = V.colwise().mean();
  Eigen::MatrixXd D = V.rowwise() - centroid;
  if (const double m = D.cwiseAbs().maxCoeff(); m > 0)
    D /= m; // no overflow in the scatter matrix
  const Eigen::Matrix3d C = D.transpose() * D;
  Eigen::Vector3d u = Eigen::Vector3d::UnitZ();
  if (o.up.cwiseAbs().maxCoeff() > 0) {
    u = o.up.stableNormalized();
  } else if (const Eigen::Vector3d axis = dominant_axis(C); axis.squaredNorm() > 0) {
    u = axis;
  }
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - u * u.transpose();
  Eigen::Vector3d a = dominant_axis(P * C * P);
  a -= a.dot(u) * u;
  if (!(a.norm() > 0.5)) { // no in-plane principal axis: use a coordinate axis
    Eigen::Index axis = 0;
    u.cwiseAbs().minCoeff(&axis);
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
    a = e - e.dot(u) * u;
  }
  a.normalize();
  const Eigen::Vector3d b = u.cross(a);
  const double az = o.azimuth_deg * kPi / 180, el = o.elevation_deg * kPi / 180;
  Camera cam;
  cam.toward = std::cos(el) * (std::cos(az) * a + std::sin(az) * b) + std::sin(el) * u;
  cam.right = -std::sin(az) * a + std::cos(az) * b;
  cam.up = cam.toward.cross(cam.right);
  return cam;
}

// Screen position in sub-pixels (x right, y down) and depth along `toward` (larger = nearer).
struct Projected {
  double x, y, z;
};

struct Projection {
  Camera cam;
  // mx, my, mz: centre of the view-space bounding box; depth is relative to mz so that float
  // depth keeps its precision for models far from the origin.
  double scale = 1, cx = 0, cy = 0, mx = 0, my = 0, mz = 0;
  Projected operator()(const Eigen::Vector3d& p) const {
    return {cx + scale * (p.dot(cam.right) - mx), cy - scale * (p.dot(cam.up) - my),
            p.dot(cam.toward) - mz};
  }
};

// Edge function of the directed edge p -> q at point s (twice the signed area of p, q, s).
inline double edge(const Projected& p, const Projected& q, double sx, double sy) {
  return (q.x - p.x) * (sy - p.y) - (q.y - p.y) * (sx - p.x);
}

// Same, evaluated with the endpoints in a canonical order so that two triangles sharing an edge
// get exactly opposite values: no pixel on a shared edge is missed by both (watertight).
inline double canonical_edge(const Projected& p, const Projected& q, double sx, double sy) {
  const bool swap = q.x < p.x || (q.x == p.x && q.y < p.y);
  return swap ? -edge(q, p, sx, sy) : edge(p, q, sx, sy);
}

std::uint8_t quantize(double c) {
  return static_cast<std::uint8_t>(std::lround(c > 0 ? std::min(c, 1.0) * 255.0 : 0.0));
}

// sRGB transfer functions (IEC 61966-2-1). Shading and the box filter work in linear light.
double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double linear_to_srgb(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

// Linear light -> 8-bit sRGB through a table (deterministic, avoids a pow per pixel).
class SrgbEncoder {
public:
  SrgbEncoder() {
    for (int i = 0; i <= kSize; ++i)
      table_[static_cast<std::size_t>(i)] =
          quantize(linear_to_srgb(static_cast<double>(i) / kSize));
  }
  std::uint8_t operator()(double linear) const {
    const double x = linear > 0 ? std::min(linear, 1.0) * kSize : 0.0; // NaN -> 0
    return table_[static_cast<std::size_t>(std::lround(x))];
  }

private:
  static constexpr int kSize = 8192;
  std::array<std::uint8_t, kSize + 1> table_{};
};

struct Lights {
  Eigen::Vector3d toward, key, fill, sky; // unit vectors in model space
  Eigen::Vector3d base;                   // linear base colour
};

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Radiance reflected from a simple photo studio: dark floor, bright soft sky above a horizon
// band, and soft boxes in the key and fill lights' directions. r is a unit reflection direction.
double studio(const Eigen::Vector3d& r, const Lights& L) {
  const double up = r.dot(L.sky);
  const double sky = 0.03 + 0.85 * smoothstep(-0.1, 0.6, up);
  const double key = 2.5 * std::pow(std::max(0.0, r.dot(L.key)), 32.0);
  const double fill = 0.8 * std::pow(std::max(0.0, r.dot(L.fill)), 12.0);
  return sky + key + fill;
}

// Linear RGB of a surface point with unit normal n facing the camera: a blue-grey metal made of a
// diffuse part (key light, fill light, headlight, sky/ground ambient) and a reflection of the
// studio weighted by a Schlick Fresnel term.
Eigen::Vector3d shade(const Eigen::Vector3d& n, const Lights& L) {
  const double nv = std::max(0.0, n.dot(L.toward));
  const double ambient = 0.04 + 0.10 * (0.5 + 0.5 * n.dot(L.sky));
  const double diffuse =
      ambient + 0.9 * std::max(0.0, n.dot(L.key)) + 0.35 * std::max(0.0, n.dot(L.fill)) + 0.25 * nv;
  const Eigen::Vector3d r = 2 * n.dot(L.toward) * n - L.toward;
  const double fresnel = 0.3 + 0.7 * std::pow(1 - nv, 5.0);
  return 0.8 * diffuse * L.base + fresnel * studio(r, L) * (0.5 * L.base.array() + 0.3).matrix();
}

} // namespace

Image render_preview(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                     const std::vector<Eigen::MatrixXd>& polylines, const PreviewOptions& options) {
  check_inputs(V, F, polylines, options);
  const int k = options.supersample;
  const int W = options.width * k, H = options.height * k; // sub-pixel grid
  const std::size_t nsub = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);

  // Camera and fit: the bounding box of mesh and polylines in the view plane spans kFill of the
  // frame along its tighter direction and is centred.
  Projection proj;
  proj.cam = make_camera(V, options);
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  double zlo = xlo, zhi = -xlo;
  auto extend = [&](const Eigen::Vector3d& p) {
    const double x = p.dot(proj.cam.right), y = p.dot(proj.cam.up), z = p.dot(proj.cam.toward);
    xlo = std::min(xlo, x), xhi = std::max(xhi, x);
    ylo = std::min(ylo, y), yhi = std::max(yhi, y);
    zlo = std::min(zlo, z), zhi = std::max(zhi, z);
  };
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    extend(V.row(i).transpose());
  for (const auto& P : polylines)
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      extend(P.row(i).transpose());
  if (!std::isfinite(xhi - xlo) || !std::isfinite(yhi - ylo) || !std::isfinite(zhi - zlo))
    fail("coordinates too large");
  const double inf = std::numeric_limits<double>::infinity();
  const double sx = xhi > xlo ? W / (xhi - xlo) : inf, sy = yhi > ylo ? H / (yhi - ylo) : inf;
  proj.scale = std::min(sx, sy) < inf ? kFill * std::min(sx, sy) : 1.0;
  proj.cx = 0.5 * W, proj.cy = 0.5 * H;
  proj.mx = 0.5 * (xlo + xhi), proj.my = 0.5 * (ylo + yhi), proj.mz = 0.5 * (zlo + zhi);

  // Vertices in screen space; per-face facing sign (two-sided shading) and unit normal.
  const Eigen::Index nv = V.rows(), nf = F.rows();
  std::vector<Projected> S(static_cast<std::size_t>(nv));
  for (Eigen::Index i = 0; i < nv; ++i)
    S[static_cast<std::size_t>(i)] = proj(V.row(i).transpose());
  std::vector<std::array<int, 3>> faces(static_cast<std::size_t>(nf));
  std::vector<Eigen::Vector3d> area_normal(static_cast<std::size_t>(nf)); // |n| = 2 * area
  std::vector<Eigen::Vector3d> unit_normal(static_cast<std::size_t>(nf));
  std::vector<double> facing(static_cast<std::size_t>(nf));
  for (Eigen::Index f = 0; f < nf; ++f) {
    const std::size_t fi = static_cast<std::size_t>(f);
    const std::array<int, 3> t{F(f, 0), F(f, 1), F(f, 2)};
    faces[fi] = t;
    const Eigen::Vector3d p0 = V.row(t[0]).transpose(), p1 = V.row(t[1]).transpose(),
                          p2 = V.row(t[2]).transpose();
    area_normal[fi] = (p1 - p0).cross(p2 - p0);
    unit_normal[fi] = area_normal[fi].normalized();
    facing[fi] = area_normal[fi].dot(proj.cam.toward) < 0 ? -1.0 : 1.0;
  }
  // Smooth normal at each face corner: the area-weighted mean of the normals of the faces around
  // that vertex, leaving out faces that bend away by more than the crease angle (box edges and
  // sharp trailing edges stay crisp; inconsistently oriented neighbours are not averaged in).
  const double crease_cos = 0.5; // 60 degrees
  std::vector<int> first(static_cast<std::size_t>(nv) + 1, 0), incident(3 * faces.size());
  for (const auto& t : faces)
    for (int v : t)
      ++first[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(nv); ++v)
    first[v + 1] += first[v];
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int v : faces[f])
        incident[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] =
            static_cast<int>(f);
  }
  std::vector<std::array<Eigen::Vector3d, 3>> corner_normal(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::size_t v = static_cast<std::size_t>(faces[f][static_cast<std::size_t>(c)]);
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (int e = first[v]; e < first[v + 1]; ++e) {
        const std::size_t g = static_cast<std::size_t>(incident[static_cast<std::size_t>(e)]);
        if (unit_normal[g].dot(unit_normal[f]) >= crease_cos)
          n += area_normal[g];
      }
      corner_normal[f][static_cast<std::size_t>(c)] = n;
    }

  // Rasterise: nearest depth and triangle id per sub-pixel (pixel centres at i + 0.5).
  std::vector<float> depth(nsub, -std::numeric_limits<float>::infinity());
  std::vector<std::int32_t> id(nsub, -1);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const auto& t = faces[static_cast<std::size_t>(f)];
    const Projected &a = S[static_cast<std::size_t>(t[0])], &b = S[static_cast<std::size_t>(t[1])],
                    &c = S[static_cast<std::size_t>(t[2])];
    const double area = edge(a, b, c.x, c.y);
    if (area == 0)
      continue;
    const double sgn = area > 0 ? 1.0 : -1.0;
    const int i0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x, b.x, c.x}) - 0.5)));
    const int i1 = std::min(W - 1, static_cast<int>(std::floor(std::max({a.x, b.x, c.x}) - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y, b.y, c.y}) - 0.5)));
    const int j1 = std::min(H - 1, static_cast<int>(std::floor(std::max({a.y, b.y, c.y}) - 0.5)));
    for (int j = j0; j <= j1; ++j) {
      const double py = j + 0.5;
      for (int i = i0; i <= i1; ++i) {
        const double px = i + 0.5;
        const double w0 = sgn * canonical_edge(b, c, px, py);
        const double w1 = sgn * canonical_edge(c, a, px, py);
        const double w2 = sgn * canonical_edge(a, b, px, py);
        if (w0 < 0 || w1 < 0 || w2 < 0)
          continue;
        const double sum = w0 + w1 + w2;
        if (!(sum > 0))
          continue;
        const float z = static_cast<float>((w0 * a.z + w1 * b.z + w2 * c.z) / sum);
        const std::size_t idx = static_cast<std::size_t>(j) * W + i;
        if (z > depth[idx]) {
          depth[idx] = z;
          id[idx] = static_cast<std::int32_t>(f);
        }
      }
    }
  }

  // Polylines: capsules of width kLineWidth output pixels, depth-tested with a bias so that curves
  // on the surface win against their own (faceted) surface and curves behind it stay hidden.
  std::vector<std::uint8_t> line(nsub, 0);
  const double hw = 0.5 * kLineWidth * k;
  const double bias = 0.002 * (zhi - zlo) + 2.5 * k / proj.scale;
  for (const auto& P : polylines) {
    // Segments between consecutive points; a single point is a zero-length segment (a dot).
    for (Eigen::Index s = 0; s < std::max<Eigen::Index>(1, P.rows() - 1); ++s) {
      const Projected a = proj(P.row(s).transpose());
      const Projected b = proj(P.row(std::min(s + 1, P.rows() - 1)).transpose());
      const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
      const int i0 = std::max(0, static_cast<int>(std::ceil(std::min(a.x, b.x) - hw - 0.5)));
      const int i1 = std::min(W - 1, static_cast<int>(std::floor(std::max(a.x, b.x) + hw - 0.5)));
      const int j0 = std::max(0, static_cast<int>(std::ceil(std::min(a.y, b.y) - hw - 0.5)));
      const int j1 = std::min(H - 1, static_cast<int>(std::floor(std::max(a.y, b.y) + hw - 0.5)));
      for (int j = j0; j <= j1; ++j) {
        const double py = j + 0.5;
        for (int i = i0; i <= i1; ++i) {
          const double px = i + 0.5;
          const double u =
              len2 > 0 ? std::clamp(((px - a.x) * dx + (py - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
          const double ex = px - (a.x + u * dx), ey = py - (a.y + u * dy);
          if (ex * ex + ey * ey > hw * hw)
            continue;
          const std::size_t idx = static_cast<std::size_t>(j) * W + i;
          if (a.z + u * (b.z - a.z) + bias >= depth[idx])
            line[idx] = 1;
        }
      }
    }
  }

  // Lights in model space, fixed to the camera: headlight, key light from the upper left front,
  // sky/ground ambient along the screen's up.
  Lights L;
  L.toward = proj.cam.toward;
  L.key = (-0.55 * proj.cam.right + 0.65 * proj.cam.up + 0.52 * proj.cam.toward).normalized();
  L.fill = (0.8 * proj.cam.right + 0.15 * proj.cam.up + 0.55 * proj.cam.toward).normalized();
  L.sky = proj.cam.up;
  L.base = kBase.unaryExpr([](double c) { return srgb_to_linear(c); });
  const Eigen::Vector3d line_linear = kLine.unaryExpr([](double c) { return srgb_to_linear(c); });
  const SrgbEncoder encode;

  // Resolve: shade every sub-pixel and box-filter k x k blocks. The background is constant per
  // output row (its vertical gradient evaluated at the row centre).
  Image image;
  image.width = options.width;
  image.height = options.height;
  image.rgb.assign(static_cast<std::size_t>(image.width) * image.height * 3, 0);
  const double inv = 1.0 / (k * k);
  for (int y = 0; y < image.height; ++y) {
    const double t = image.height > 1 ? (y + 0.5) / image.height : 0.5;
    const Eigen::Vector3d bg = (1 - t) * options.background_top + t * options.background_bottom;
    const Eigen::Vector3d bg_linear = bg.unaryExpr([](double c) { return srgb_to_linear(c); });
    for (int x = 0; x < image.width; ++x) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int nbg = 0;
      for (int j = y * k; j < (y + 1) * k; ++j) {
        for (int i = x * k; i < (x + 1) * k; ++i) {
          const std::size_t idx = static_cast<std::size_t>(j) * W + i;
          if (line[idx]) {
            sum += line_linear;
          } else if (id[idx] >= 0) {
            const auto& tri = faces[static_cast<std::size_t>(id[idx])];
            const Projected &a = S[static_cast<std::size_t>(tri[0])],
                            &b = S[static_cast<std::size_t>(tri[1])],
                            &c = S[static_cast<std::size_t>(tri[2])];
            const double px = i + 0.5, py = j + 0.5;
            const double area = edge(a, b, c.x, c.y);
            const double l0 = edge(b, c, px, py) / area, l1 = edge(c, a, px, py) / area;
            const double l2 = 1 - l0 - l1;
            const std::size_t f = static_cast<std::size_t>(id[idx]);
            const auto& cn = corner_normal[f];
            Eigen::Vector3d n = facing[f] * (l0 * cn[0] + l1 * cn[1] + l2 * cn[2]).normalized();
            // Interpolated normals turned away from the face (degenerate neighbourhoods): use the
            // flat face normal.
            if (!(n.dot(facing[f] * unit_normal[f]) > 0))
              n = facing[f] * unit_normal[f];
            sum += shade(n, L);
          } else {
            ++nbg;
          }
        }
      }
      std::uint8_t* out = &image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3];
      if (nbg == k * k) { // pure background: exactly its sRGB colour
        for (int ch = 0; ch < 3; ++ch)
          out[ch] = quantize(bg(ch));
      } else {
        const Eigen::Vector3d colour = (sum + nbg * bg_linear) * inv;
        for (int ch = 0; ch < 3; ++ch)
          out[ch] = encode(colour(ch));
      }
    }
  }
  return image;
}

void write_png(const std::string& path, const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw std::invalid_argument("write_png: image size does not match its pixel buffer");
  AtomicPath out(path);
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&png, out.temp().c_str(), 0, image.rgb.data(), 0, nullptr)) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw std::runtime_error("cannot write " + path + ": " + reason);
  }
  out.commit();
}

void write_preview_png(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       const std::vector<Eigen::MatrixXd>& polylines,
                       const PreviewOptions& options) {
  write_png(path, render_preview(V, F, polylines, options));
}

} // namespace interlin
