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

TEST_CASE("CLI: a body far from the origin written to STL warns that floats round its "
          "coordinates, PLY keeps them",
          "[cli][precision]") {
  // A unit ball at (1e5, -2e5, 3e4): floats near 2e5 are 1/64 apart, rounding by up to 0.0078,
  // 0.0023 of the ball's 3.5 box diagonal (the warning's bound is 1e-5 of it). The same ball at the
  // origin (rounding 6e-8) and the PLY file (doubles) give no warning; -q none either.
  const TempDir d("cli-precision-far");
  const std::string far = d / "far.rf", near = d / "near.rf";
  write_file(far, "box(99998.5, -200001.5, 29998.5, 100001.5, -199998.5, 30001.5);\n"
                  "res = sphere(x - 100000, y + 200000, z - 30000, 1);\n");
  write_file(near, "box(-1.5,-1.5,-1.5,1.5,1.5,1.5);\nres = sphere(x, y, z, 1);\n");
  const std::string kWarning = "far.stl stores single-precision coordinates: at 2e+05 from the "
                               "origin they round by up to 0.0078";
  const Run stl = run("mesh " + far + " -o " + (d / "far.stl") + " --resolution 16");
  INFO(stl.out << stl.err);
  CHECK(stl.status == 0);
  CHECK_THAT(stl.err, Catch::Contains(kWarning));
  CHECK_THAT(stl.out,
             Catch::Contains("  box          [99998.5, 100001.5] x [-200001.5, -199998.5]"));
  for (const std::string& cmd : {"mesh " + far + " -o " + (d / "far.ply") + " --resolution 16",
                                 "mesh " + far + " -o " + (d / "q.stl") + " --resolution 16 -q",
                                 "mesh " + near + " -o " + (d / "near.stl") + " --resolution 16"}) {
    const Run r = run(cmd);
    INFO(cmd << "\n" << r.err);
    CHECK(r.status == 0);
    CHECK(r.err.find("single-precision") == std::string::npos);
  }
}
