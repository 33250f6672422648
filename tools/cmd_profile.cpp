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

// The body of `interlin profile` (run_command handles help, exit statuses and removal on
// failure).
void profile_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const std::string input = single_input(a, "parameter file");
  if (const std::string ext = lower_extension(input); ext != ".json" && ext != ".toml")
    throw UsageError("parameter file '" + input + "': expected a .json or .toml file");
  if (!a.has("output"))
    throw UsageError("nothing to do: give -o SECTIONS.csv");
  const std::string output = a.get("output");
  require_csv("output", output);
  const std::string curv = a.get("curvature");
  if (a.has("curvature"))
    require_csv("--curvature", curv);
  std::string joint, stack;
  if (a.has("joint"))
    joint = parse_choice("joint", a.get("joint"), {"g2", "g3"});
  if (a.has("stack"))
    stack = parse_choice("stack", a.get("stack"), {"centroid", "le", "te", "none"});
  std::pair<int, int> points{0, 0};
  if (a.has("points")) {
    points = parse_int_pair("points", a.get("points"), 2, 100000);
    if (points.first < 4 || points.second % 2 != 0)
      throw UsageError("--points SIDE,EDGE: SIDE must be >= 4 and EDGE even");
  }
  const bool quiet = a.has("quiet");
  const long long max_points = limit_option(a, "max-points", limits::profile_points);
  check_outputs({input}, a.has("curvature") ? std::vector{output, curv} : std::vector{output});

  if (!quiet)
    std::cerr << "reading " << input << "\n";
  ProfileJob job = read_profile_parameters(input);
  if (!joint.empty())
    job.options.joint = joint == "g2" ? CascadeJoint::g2_quadratic : CascadeJoint::g3_cubic;
  if (!stack.empty())
    job.align = kAligns.at(stack);
  if (points.first > 0) {
    job.options.side_intervals = points.first;
    job.options.edge_intervals = points.second;
  }
  const long long per_profile = 2LL * (job.options.side_intervals + job.options.edge_intervals);
  if (const long long n = per_profile * static_cast<long long>(job.stations.size()); n > max_points)
    throw LimitError(input + ": " + std::to_string(job.stations.size()) + " profile(s) of " +
                         std::to_string(per_profile) + " points ask for " + std::to_string(n) +
                         " points, more than the limit of " + std::to_string(max_points),
                     "max-points");

  std::vector<Section> sections;
  std::vector<CascadeProfile> profiles;
  try {
    std::vector<Eigen::MatrixXd> S;
    if (job.has_span) {
      S = stack_cascade_profiles(job.stations, job.align, job.options, &profiles);
    } else { // one profile in the cascade frame, z = 0
      profiles.push_back(cascade_profile(job.stations[0].parameters, job.options));
      S.emplace_back(profiles[0].points.rows(), 3);
      S[0] << profiles[0].points, Eigen::VectorXd::Zero(profiles[0].points.rows());
    }
    for (size_t k = 0; k < S.size(); ++k) {
      Section s;
      s.id = std::to_string(k);
      s.points = S[k];
      sections.push_back(s);
    }
  } catch (const std::invalid_argument& e) {
    throw_input_error(input, 0, e.what()); // a property of the file's parameters
  } catch (const std::runtime_error& e) {
    throw_input_error(input, 0, e.what());
  }

  std::cout << "interlin profile " << input << "\n";
  std::cout << "  sections     " << sections.size() << " x " << sections[0].points.rows()
            << " points, joint "
            << (job.options.joint == CascadeJoint::g3_cubic ? "G3 (cubic, §4.2)"
                                                            : "G2 (quadratic, §4.1)")
            << "\n";
  for (size_t k = 0; k < profiles.size(); ++k) {
    const CascadeProfile& P = profiles[k];
    const auto len = [](const std::vector<PlanarNaturalCurve>& side) {
      return side[0].length + side[1].length;
    };
    std::cout << "  section " << k << "    z " << fmt(job.stations[k].radius, 6) << ", pitch "
              << fmt(P.pitch, 6) << ", throat " << fmt(P.throat, 6) << ", suction "
              << fmt(len(P.suction), 6) << ", pressure " << fmt(len(P.pressure), 6) << ", max miss "
              << fmt(P.miss, 2) << "\n";
  }

  write_sections_csv(output, sections);
  written.push_back(output);
  if (a.has("curvature")) {
    write_file_atomically(curv, [&](std::ostream& out) {
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
    written.push_back(curv);
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
