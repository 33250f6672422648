// interlin implicit SCAN.{pcd,ply,xyz,csv,...}: a point cloud -> .ifl. A sectioned scan (points
// on parallel planes or coaxial cylinders) becomes fitted sections -> loft -> the section body
// of issue 10 (exact on the loft through the fitted sections); any other cloud the multi-level
// partition of unity of local fits (cloud_implicit.h, kind cloud_pu) or, for sparse clouds, the
// Hermite RBF interpolant (hermite_rbf.h, kind cloud_hrbf; --fit).
#include "implicit_jobs.h"

#include "interlin/reconstruction/clouds/choose_cloud_fit.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"
#include "interlin/reconstruction/clouds/fit_sliced_scan.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>
#include <iostream>
#include <memory>

namespace interlin::cli {

namespace {

const std::vector<const char*> kBodyOptions = {"resolution", "band", "margin", "span-smoothing"};

SliceKind slice_option(const ParsedArgs& a) {
  const std::string s =
      parse_choice("slices", a.get("slices", "auto"), {"auto", "planar", "radial", "none"});
  return s == "planar"   ? SliceKind::planar
         : s == "radial" ? SliceKind::radial
         : s == "none"   ? SliceKind::none
                         : SliceKind::automatic;
}

CloudPrepOptions prep_options(const ParsedArgs& a, const Progress& progress) {
  CloudPrepOptions o;
  o.outlier_neighbours = parse_int("outliers", a.get("outliers", "16"), 0, 1000);
  o.outlier_ratio = parse_double("outlier-ratio", a.get("outlier-ratio", "3"));
  if (!(o.outlier_ratio > 0))
    throw UsageError("--outlier-ratio: expected a number > 0");
  o.voxel = parse_double("voxel", a.get("voxel", "0"));
  if (!(o.voxel >= 0))
    throw UsageError("--voxel: expected a leaf size >= 0 (0: no downsampling)");
  const std::string n =
      parse_choice("normals", a.get("normals", "auto"), {"auto", "file", "estimate"});
  o.normals = n == "file"       ? NormalSource::file
              : n == "estimate" ? NormalSource::estimate
                                : NormalSource::automatic;
  const std::string k = a.get("normal-neighbours", "auto");
  try {
    o.normal_neighbours = k == "auto" ? 0 : parse_int("normal-neighbours", k, 3, 1000);
  } catch (const UsageError&) {
    throw UsageError("--normal-neighbours expects auto or an integer in [3, 1000], got '" + k +
                     "'");
  }
  const std::string sheets =
      parse_choice("sheet-normals", a.get("sheet-normals", "auto"), {"auto", "on", "off"});
  o.sheet_normals = sheets == "on"    ? SheetNormals::on
                    : sheets == "off" ? SheetNormals::off
                                      : SheetNormals::automatic;
  o.threads = parse_int("threads", a.get("threads", "0"), 0, 4096);
  o.progress = progress;
  return o;
}

// A note on stderr for options the chosen path does not use (the path is known only after
// slice detection when --slices is auto).
void unused(const ParsedArgs& a, const std::vector<const char*>& options, const std::string& why,
            const Progress& progress) {
  for (const char* o : options)
    if (a.has(o) && !progress.quiet)
      std::cerr << "note: --" << o << " ignored: " << why << "\n";
}

void sectioned(const ParsedArgs& a, const PointCloud& c, const SliceFamily& family, double noise,
               SectionBodyOptions bo, const std::string& output, const Progress& progress) {
  unused(a, {"max-depth", "fit", "smooth-points"}, "it applies to the unstructured fit", progress);
  SliceFitOptions so;
  so.noise = noise;
  so.threads = bo.threads;
  so.progress = progress;
  so.smooth_span = a.get("span-smoothing", "auto") == "auto";
  progress("fitting " + std::to_string(family.members.size()) + " sections");
  const SlicedFit fit = fit_sliced_scan(c.points, family, so);
  int cmin = 1 << 30, cmax = 0;
  double rms = 0;
  for (const FittedSection& s : fit.sections) {
    cmin = std::min(cmin, s.control);
    cmax = std::max(cmax, s.control);
    rms = std::max(rms, s.rms);
  }
  std::cout << "  slices       " << (family.kind == SliceKind::planar ? "planar" : "radial") << ", "
            << family.members.size() << " along (" << fmt(family.axis(0), 3) << ", "
            << fmt(family.axis(1), 3) << ", " << fmt(family.axis(2), 3) << "), stations "
            << fmt(family.stations.front()) << " .. " << fmt(family.stations.back()) << ", spread "
            << fmt(family.spread, 3) << "\n";
  std::cout << "  fit          closed cubics of " << cmin << " .. " << cmax
            << " control points, noise " << fmt(fit.noise, 3)
            << (noise > 0 ? " (given)" : " (the slices' spread)") << ", largest rms residual "
            << fmt(rms, 3) << "; fitted curves to the loft " << fmt(fit.section_gap, 3) << "\n";
  std::cout << "  span         "
            << (fit.span_control > 0
                    ? "smoothed: the sections are isocurves of one surface with " +
                          std::to_string(fit.span_control) + " control points along the span"
                    : std::string("each section fitted to its slice alone"))
            << "\n";
  progress("implicit body of the loft");
  const SectionBodyBuild b = build_section_body(fit.loft, bo);
  print_section_body(b, std::to_string(fit.sections.size()) + " fitted");
  progress("writing " + output);
  write_model(output, to_ifl(b.model));
}

// --fit: hrbf, pu, or auto: the hold-out's choice where hermite_rbf_offered.
bool use_hermite_rbf(const std::string& input, const PointCloud& c, const std::string& fit,
                     bool normals_estimated, const CloudFitOptions& fo, const Progress& progress) {
  if (fit == "hrbf") {
    if (c.points.rows() > kHermiteRbfMaxPoints)
      throw_input_error(input, 0,
                        "--fit hrbf takes at most " + std::to_string(kHermiteRbfMaxPoints) +
                            " points, the cloud has " + std::to_string(c.points.rows()) +
                            " (use --fit pu or --voxel to thin it)");
    return true;
  }
  if (fit == "pu" || !hermite_rbf_offered(c, !normals_estimated))
    return false;
  progress("choosing the fit: five-fold hold-out of the partition of unity and the Hermite RBF");
  const CloudFitChoice choice = choose_cloud_fit(c, fo);
  std::cout << "  choice       hold-out mean |F| / |grad F|: partition of unity "
            << fmt(choice.holdout_pu, 3) << ", Hermite RBF " << fmt(choice.holdout_hrbf, 3)
            << " -> " << (choice.hermite ? "Hermite RBF" : "partition of unity") << "\n";
  return choice.hermite;
}

void hermite(const std::string& input, const PointCloud& c, const std::string& output,
             const Progress& progress) {
  progress("fitting the Hermite RBF interpolant (" + std::to_string(c.points.rows()) + " points)");
  HermiteRbfInfo info;
  HermiteRbf model;
  try {
    model = fit_hermite_rbf(c, &info);
  } catch (const std::invalid_argument& e) {
    throw_input_error(input, 0, e.what());
  }
  std::cout << "  fit          Hermite RBF through " << c.points.rows()
            << " points and their normals; point spacing " << fmt(info.spacing, 4)
            << (info.flipped ? "; the normals pointed inward: F negated" : "") << "\n";
  progress("writing " + output);
  write_model(output, to_ifl(model));
}

void unstructured(const std::string& input, PointCloud& c, const CloudPrepOptions& po,
                  CloudPrepReport& rep, CloudFitOptions fo, const std::string& fit,
                  const std::string& output, const Progress& progress) {
  std::vector<std::string> notes;
  cloud_normals(input, c, po, rep, &notes);
  if (!progress.quiet)
    for (const std::string& n : notes)
      std::cerr << "note: " << n << "\n";
  std::cout << "  normals      "
            << (rep.normals_estimated
                    ? "estimated (PCL, k = " + std::to_string(rep.normal_neighbours) +
                          (rep.sheet_normals
                               ? "; kept to one sheet, " + std::to_string(rep.sheet_changed) +
                                     " more than 20 degrees from PCA's"
                               : std::string()) +
                          ") and oriented"
                : rep.normals_reoriented ? "from the file, re-oriented"
                                         : "from the file")
            << (rep.patches_flipped > 0
                    ? "; " + std::to_string(rep.patches_flipped) + " turned by the winding number"
                    : std::string())
            << "\n";
  if (use_hermite_rbf(input, c, fit, rep.normals_estimated, fo, progress)) {
    hermite(input, c, output, progress);
    return;
  }
  CloudFitInfo info;
  progress("fitting the partition of unity");
  auto model = std::make_shared<const CloudImplicit>(fit_cloud_implicit(c, fo, &info));
  std::cout << "  noise        sigma = " << fmt(info.noise, 3)
            << (info.noise_estimated ? " (estimated from the points)" : " (given)")
            << "; point spacing " << fmt(info.spacing, 4) << "\n";
  if (info.smoothed_points > 0)
    std::cout << "  smoothing    " << info.smoothed_points
              << " points moved onto local quadrics (median " << info.smoothing_neighbours
              << " neighbours, " << info.smoothed_on_edges << " onto edge sheets, scan noise "
              << fmt(info.smoothing_noise, 3) << ")\n";
  std::cout << "  octree       " << info.leaves << " leaves (" << info.two_sheet_leaves
            << " with two sheets, " << info.far_leaves << " far from the points, "
            << info.sign_fixed_leaves << " re-signed by the winding number, "
            << info.exterior_negated_leaves << " negated to the flood fill's side; "
            << info.exterior_split_cells + info.slab_split_cells
            << " cells split at thin edges), depth " << info.depth << ", " << info.min_points
            << " points per fit" << (info.flipped ? "; the normals pointed inward: F negated" : "")
            << "\n";
  std::cout << "  fit          |F| / |grad F| at the points: rms " << fmt(info.rms_distance, 3)
            << ", max " << fmt(info.max_distance, 3) << "; " << fmt(100 * info.within_3_sigma, 4)
            << " % within 3 sigma\n";
  progress("writing " + output);
  write_model(output, to_ifl(*model, info.noise));
}

} // namespace

void cloud_job(const ParsedArgs& a, const std::string& input, const std::string& output,
               const Progress& progress, const std::string& why) {
  for (const char* o : {"set", "var", "mesh-resolution"})
    if (a.has(o))
      throw UsageError(std::string("--") + o + " applies to R-function models (.rf) only");
  const SliceKind kind = slice_option(a);
  if (kind == SliceKind::none)
    for (const char* o : kBodyOptions)
      if (a.has(o))
        throw UsageError(std::string("--") + o +
                         " applies to sections and sectioned scans (not with --slices none)");
  for (const char* o : {"max-depth", "smooth-points"})
    if (kind != SliceKind::none && kind != SliceKind::automatic && a.has(o))
      throw UsageError(std::string("--") + o +
                       " applies to the unstructured fit (not with --slices " + a.get("slices") +
                       ")");
  double noise = 0;
  if (a.has("noise")) {
    noise = parse_double("noise", a.get("noise"));
    if (!(noise > 0))
      throw UsageError("--noise: expected a standard deviation > 0");
  }
  if (const std::string m = a.get("span-smoothing", "auto"); m != "auto" && m != "off")
    throw UsageError("--span-smoothing: expected auto or off, got '" + m + "'");
  const std::string fit = parse_choice("fit", a.get("fit", "auto"), {"auto", "pu", "hrbf"});
  for (const char* o : {"max-depth", "smooth-points"})
    if (fit == "hrbf" && a.has(o))
      throw UsageError(std::string("--") + o +
                       " applies to the partition of unity (not with --fit hrbf)");
  // Every option is checked before any work.
  const CloudPrepOptions po = prep_options(a, progress);
  CloudFitOptions fo;
  fo.noise = noise;
  fo.max_depth = parse_int("max-depth", a.get("max-depth", "12"), 1, 20);
  fo.smooth_points =
      parse_choice("smooth-points", a.get("smooth-points", "auto"), {"auto", "off"}) == "auto";
  fo.threads = po.threads;
  fo.progress = progress;
  const SectionBodyOptions bo = section_body_options(a, progress);
  progress("reading " + input);
  std::vector<std::string> notes;
  const PointCloud raw = read_point_cloud(input, &notes);
  CloudPrepReport rep;
  PointCloud c = filter_cloud(input, raw, po, rep, &notes);
  if (!progress.quiet)
    for (const std::string& n : notes)
      std::cerr << "note: " << n << "\n";
  std::cout << "interlin implicit " << input << "\n";
  std::cout << "  input        " << why << "\n";
  std::cout << "  points       " << rep.read << " read, " << rep.distinct << " distinct, "
            << rep.outliers << " outliers removed, " << rep.kept << " kept\n";
  if (kind != SliceKind::none) {
    progress("detecting slices");
    const SliceFamily family = detect_slices(c.points, kind);
    if (family.kind != SliceKind::none) {
      sectioned(a, c, family, noise, bo, output, progress);
      return;
    }
    if (kind != SliceKind::automatic)
      throw_input_error(input, 0,
                        std::string("no ") + (kind == SliceKind::planar ? "planar" : "radial") +
                            " slices found (3 or more thin slices of closed profiles, "
                            "docs/formats.md); use --slices auto or none for an unstructured fit");
    std::cout << "  slices       none found: unstructured fit\n";
    unused(a, kBodyOptions, "no slices were found (they apply to sectioned scans)", progress);
  }
  unstructured(input, c, po, rep, fo, fit, output, progress);
}

} // namespace interlin::cli
