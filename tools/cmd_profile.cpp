// interlin profile: the 13 cascade parameters (seed 004 §4.1–4.2) -> blade profile(s) as a
// section CSV, one profile or a span stack that `interlin loft` accepts.
#include "cli_common.h"
#include "commands.h"
#include "profile_parameters.h"

#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/splines/cascade_stack.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

namespace interlin::cli {

const char* const kProfileHelp =
    R"(interlin profile - axial-turbine cascade profile(s) from 13 parameters -> section CSV

Usage: interlin profile PARAMS.{json,toml} -o SECTIONS.csv [options]

Input: a JSON or TOML file with the book's 13 parameters (seed 004 §4.1; docs/formats.md, "Cascade
profile parameters"), optionally a "span" law: per-radius values of any parameter (axial
width ~ chord, stagger, thickness, ...), which stacks one profile per radius.

Output: a section CSV (section,index,x,y,z): one closed profile per section, in the plane
z = radius (z = 0 without a span law), numbered from the middle of the trailing edge towards
the suction side, all sections with the same point count, so `interlin loft` lofts the stack.

Options:
  -o, --output FILE          the section CSV (.csv), written whole or not at all
  --joint g2|g3              joint after the throat / max-thickness point: quadratic curvature
                             (G2, §4.1) or cubic (G3, §4.2, default); overrides the file
  --points SIDE,EDGE         intervals along each side and each edge arc (EDGE even);
                             default 60,16; overrides the file
  --stack centroid|le|te|none
                             stacking line of a span law: area centroid (default), leading-
                             or trailing-edge centre, or the cascade frame; overrides the file
  --curvature FILE           curvature-plot data (.csv): section,side,sbar,s,x,y,phi,k,dk
  --max-points N             profile points the file and --points may ask for, all sections
                             together (default 10000000)
  -q, --quiet                no progress lines on stderr
  -h, --help                 this help

Examples:
  interlin profile data/profiles/turbine_nozzle.json -o profile.csv --curvature k.csv
  interlin profile data/profiles/turbine_blade_span.toml -o blade.csv
  interlin loft blade.csv -o blade.stl --cap
)";

namespace {

void require_csv(const std::string& option, const std::string& path) {
  if (lower_extension(path) != ".csv")
    throw UsageError(option + " '" + path + "': expected a .csv file");
}

// The command line of `interlin profile`, checked.
struct ProfileRequest {
  std::string input, output, curvature; // curvature: "" unless --curvature
  std::string joint, stack;             // "" unless given
  std::pair<int, int> points{0, 0};     // --points SIDE,EDGE, {0, 0} unless given
  bool quiet = false;
  long long max_points = 0;
};

ProfileRequest profile_request(const ParsedArgs& a) {
  ProfileRequest r;
  r.input = single_input(a, "parameter file");
  if (const std::string ext = lower_extension(r.input); ext != ".json" && ext != ".toml")
    throw UsageError("parameter file '" + r.input + "': expected a .json or .toml file");
  if (!a.has("output"))
    throw UsageError("nothing to do: give -o SECTIONS.csv");
  r.output = a.get("output");
  require_csv("output", r.output);
  if (a.has("curvature")) {
    r.curvature = a.get("curvature");
    require_csv("--curvature", r.curvature);
  }
  if (a.has("joint"))
    r.joint = parse_choice("joint", a.get("joint"), {"g2", "g3"});
  if (a.has("stack"))
    r.stack = parse_choice("stack", a.get("stack"), {"centroid", "le", "te", "none"});
  if (a.has("points")) {
    r.points = parse_int_pair("points", a.get("points"), 2, 100000);
    if (r.points.first < 4 || r.points.second % 2 != 0)
      throw UsageError("--points SIDE,EDGE: SIDE must be >= 4 and EDGE even");
  }
  r.quiet = a.has("quiet");
  r.max_points = limit_option(a, "max-points", limits::profile_points);
  return r;
}

// The parameter file with the command line's overrides, within the --max-points limit.
ProfileJob profile_job(const ProfileRequest& r) {
  ProfileJob job = read_profile_parameters(r.input);
  if (!r.joint.empty())
    job.options.joint = r.joint == "g2" ? CascadeJoint::g2_quadratic : CascadeJoint::g3_cubic;
  if (!r.stack.empty())
    job.align = kAligns.at(r.stack);
  if (r.points.first > 0) {
    job.options.side_intervals = r.points.first;
    job.options.edge_intervals = r.points.second;
  }
  const long long per_profile = 2LL * (job.options.side_intervals + job.options.edge_intervals);
  if (const long long n = per_profile * static_cast<long long>(job.stations.size());
      n > r.max_points)
    throw LimitError(r.input + ": " + std::to_string(job.stations.size()) + " profile(s) of " +
                         std::to_string(per_profile) + " points ask for " + std::to_string(n) +
                         " points, more than the limit of " + std::to_string(r.max_points),
                     "max-points");
  return job;
}

// The profiles of the job as sections (one profile in the cascade frame at z = 0 without a span
// law); a parameter set the construction rejects is an input error of the file.
std::vector<Section> profile_sections(const ProfileJob& job, const std::string& input,
                                      std::vector<CascadeProfile>& profiles) {
  std::vector<Section> sections;
  try {
    std::vector<Eigen::MatrixXd> S;
    if (job.has_span) {
      S = stack_cascade_profiles(job.stations, job.align, job.options, &profiles);
    } else {
      profiles.push_back(cascade_profile(job.stations[0].parameters, job.options));
      S.emplace_back(profiles[0].points.rows(), 3);
      S[0] << profiles[0].points, Eigen::VectorXd::Zero(profiles[0].points.rows());
    }
    for (size_t k = 0; k < S.size(); ++k) {
      Section section;
      section.id = std::to_string(k);
      section.points = S[k];
      sections.push_back(section);
    }
  } catch (const std::invalid_argument& e) {
    throw_input_error(input, 0, e.what());
  } catch (const std::runtime_error& e) {
    throw_input_error(input, 0, e.what());
  }
  return sections;
}

void print_profile_summary(const std::string& input, const ProfileJob& job,
                           const std::vector<Section>& sections,
                           const std::vector<CascadeProfile>& profiles) {
  std::cout << "interlin profile " << input << "\n";
  std::cout << "  sections     " << sections.size() << " x " << sections[0].points.rows()
            << " points, joint "
            << (job.options.joint == CascadeJoint::g3_cubic ? "G3 (cubic, §4.2)"
                                                            : "G2 (quadratic, §4.1)")
            << "\n";
  const auto len = [](const std::vector<PlanarNaturalCurve>& side) {
    return side[0].length + side[1].length;
  };
  for (size_t k = 0; k < profiles.size(); ++k) {
    const CascadeProfile& P = profiles[k];
    std::cout << "  section " << k << "    z " << fmt(job.stations[k].radius, 6) << ", pitch "
              << fmt(P.pitch, 6) << ", throat " << fmt(P.throat, 6) << ", suction "
              << fmt(len(P.suction), 6) << ", pressure " << fmt(len(P.pressure), 6) << ", max miss "
              << fmt(P.miss, 2) << "\n";
  }
}

// --curvature: the curvature plot of both sides of every profile (201 samples per side).
void write_curvature_plot(const std::string& path, const std::vector<CascadeProfile>& profiles) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.precision(17);
    out << "section,side,sbar,s,x,y,phi,k,dk\n";
    for (size_t k = 0; k < profiles.size(); ++k)
      for (const auto& [name, side] : {std::pair{"suction", &profiles[k].suction},
                                       std::pair{"pressure", &profiles[k].pressure}}) {
        const Eigen::MatrixXd T = side_curvature_plot(*side, 201);
        for (Eigen::Index i = 0; i < T.rows(); ++i) {
          out << k << ',' << name;
          for (Eigen::Index c = 0; c < T.cols(); ++c)
            out << ',' << T(i, c);
          out << '\n';
        }
      }
  });
}

// The body of `interlin profile` (run_command handles help, exit statuses and removal on
// failure).
void profile_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const ProfileRequest r = profile_request(a);
  check_outputs({r.input},
                r.curvature.empty() ? std::vector{r.output} : std::vector{r.output, r.curvature});
  if (!r.quiet)
    std::cerr << "reading " << r.input << "\n";
  const ProfileJob job = profile_job(r);
  std::vector<CascadeProfile> profiles;
  const std::vector<Section> sections = profile_sections(job, r.input, profiles);
  print_profile_summary(r.input, job, sections, profiles);
  write_sections_csv(r.output, sections);
  written.push_back(r.output);
  if (!r.curvature.empty()) {
    write_curvature_plot(r.curvature, profiles);
    written.push_back(r.curvature);
  }
  print_written(written);
}

} // namespace

int run_profile(int argc, const char* const* argv) {
  return run_command("profile", kProfileHelp, argc, argv,
                     {{"output", 'o', true, false},
                      {"joint", 0, true, false},
                      {"points", 0, true, false},
                      {"stack", 0, true, false},
                      {"curvature", 0, true, false},
                      {"max-points", 0, true, false}},
                     profile_main);
}

} // namespace interlin::cli
