// interlin: spline-interlineation surface reconstruction, command-line entry point.
#include "commands.h"

#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"

#include <cstring>
#include <iostream>

namespace {

const char* const kHelp = R"(interlin - spline-interlineation surface reconstruction

Usage:
  interlin loft SECTIONS.csv -o OUT [-o OUT ...] [options]
      Closed blade sections -> one B-spline surface through every section exactly;
      writes meshes (.stl .obj .ply .off), CAD (.igs .json) and a preview (.png).
  interlin loft SECTIONS.csv --holdout K
      Accuracy study: loft every K-th section, measure the distance of the others.
  interlin loft SECTIONS.csv --guides GUIDES.csv -o OUT [...]
      Sections plus spanwise guide lines (leading/trailing edge, ...) -> one Gordon
      B-spline surface through every section and every guide exactly.
  interlin eval MODEL POINTS.csv [--gradient] [-o OUT.csv]
      Implicit model (.rf or .ifl) -> its value F (and gradient) at the points of a CSV file.
  interlin mesh MODEL -o OUT [-o OUT ...] [--resolution N | --cell H] [options]
      Implicit model (.rf or .ifl) -> closed triangle mesh of the body (.stl .obj .ply .off .png).
  interlin implicit SECTIONS.csv|SCAN.{pcd,ply,xyz,csv}|MODEL.rf -o MODEL.ifl [options]
      Sections -> implicit equation of the lofted body (0 exactly on the loft and its caps,
      the signed distance near it); a point cloud -> the same through fitted sections (a
      sectioned scan) or a partition of unity of local fits (any scan); an R-function model
      -> its normalised equation.
  interlin profile PARAMS.json -o SECTIONS.csv [--joint g2|g3] [--curvature K.csv]
      13 cascade parameters (+ optional span law) -> turbine blade profile(s) as a section
      CSV that `interlin loft` accepts (seed 004, natural parametrization).
  interlin COMMAND --help     options of a command
  interlin --version

Exit status: 0 success, 1 bad input or failed output, 2 wrong usage.
)";

} // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "interlin: no command given (see interlin --help)\n";
    return 2;
  }
  interlin::register_cloud_ifl_kind(); // .ifl files of point clouds (eval, mesh, ifl() in .rf)
  const char* cmd = argv[1];
  if (!std::strcmp(cmd, "--help") || !std::strcmp(cmd, "-h") || !std::strcmp(cmd, "help")) {
    std::cout << kHelp;
    return 0;
  }
  if (!std::strcmp(cmd, "--version")) {
    std::cout << "interlin " INTERLIN_VERSION "\n";
    return 0;
  }
  if (!std::strcmp(cmd, "loft"))
    return interlin::cli::run_loft(argc, argv);
  if (!std::strcmp(cmd, "profile"))
    return interlin::cli::run_profile(argc, argv);
  if (!std::strcmp(cmd, "eval"))
    return interlin::cli::run_eval(argc, argv);
  if (!std::strcmp(cmd, "mesh"))
    return interlin::cli::run_mesh(argc, argv);
  if (!std::strcmp(cmd, "implicit"))
    return interlin::cli::run_implicit(argc, argv);
  std::cerr << "interlin: unknown command '" << cmd << "' (see interlin --help)\n";
  return 2;
}
