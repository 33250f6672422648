// Mesh outputs in double precision: PLY and OBJ carry the coordinates interlin computed, bit for
// bit, unless --mesh-precision single asks for floats.
#include "support/cli_runner.h"

#include "interlin/reconstruction/io/mesh_io.h"

#include <catch2/catch.hpp>

using namespace interlin::test;

TEST_CASE("CLI: PLY and OBJ meshes are double precision by default, single on request",
          "[cli][precision]") {
  const TempDir d("cli-precision");
  const std::string model = d / "m.rf";
  write_file(model, "box(-1.5,-1.5,-1.5,1.5,1.5,1.5);\nres = sphere(x, y, z, 1);\n");
  REQUIRE(run("mesh " + model + " -o " + (d / "a.ply") + " -o " + (d / "a.obj") + " -o " +
              (d / "a.stl") + " --resolution 12 -q")
              .status == 0);
  REQUIRE(run("mesh " + model + " -o " + (d / "s.ply") + " -o " + (d / "s.obj") +
              " --resolution 12 --mesh-precision single -q")
              .status == 0);
  CHECK_THAT(slurp(d / "a.ply"), Catch::Contains("property double x"));
  CHECK_THAT(slurp(d / "s.ply"), Catch::Contains("property float x"));
  Eigen::MatrixXd Vply, Vobj, Vstl, Vs;
  Eigen::MatrixXi Fply, Fobj, Fstl, Fs;
  interlin::read_mesh(d / "a.ply", Vply, Fply);
  interlin::read_mesh(d / "a.obj", Vobj, Fobj);
  interlin::read_mesh(d / "s.ply", Vs, Fs);
  CHECK(Vobj == Vply); // the same doubles through both formats
  CHECK(Fobj == Fply);
  CHECK(Vs == Vply.cast<float>().cast<double>()); // single: each the nearest float
  // The computed vertices are not floats: single precision moves them, by at most 2^-24.
  const Eigen::ArrayXXd diff = (Vs - Vply).array().abs();
  CHECK(diff.maxCoeff() > 0);
  CHECK((diff <= 0x1p-24 * Vply.array().abs()).all());
  CHECK(run("mesh " + model + " -o " + (d / "x.ply") + " --mesh-precision half -q").status == 2);
}
