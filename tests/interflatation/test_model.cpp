// The .rf model language and the shipped seed models: digest values at points (000 T18, T20;
// 002 §12.2-12.3; 003 §11.3), signs inside and outside, parameters, and one clear error with
// FILE:LINE:COLUMN for every kind of mistake.
#include "rf_eval.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/rfunctions/model.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

using namespace interlin;
using test::value_at;

namespace {

constexpr double kPrinted = 5e-8; // the digests print 7 decimals (002: 6)

std::string model_path(const std::string& name) {
  return std::string(INTERLIN_DATA_DIR) + "/models/" + name;
}

ImplicitFunction model(const std::string& name, const std::string& output = "res",
                       std::map<std::string, double> parameters = {}) {
  ModelOptions o;
  o.output = output;
  o.parameters = std::move(parameters);
  return load_model(model_path(name), o);
}

// The message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const ModelOptions& o = {}) {
  try {
    parse_model(text, "m.rf", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string kBox = "box(-1, -1, -1, 1, 1, 1);\n";

} // namespace

TEST_CASE("Impeller (seed 000 Appendix B): digest T18 values", "[rf][model]") {
  const ImplicitFunction f = model("impeller.rf");
  CHECK(f.box.min() == Eigen::Vector3d(-13.2, -13.2, -0.6));
  CHECK(f.box.max() == Eigen::Vector3d(13.2, 13.2, 5.1));
  const double d = 7.5 * std::numbers::pi / 180;
  const double pts[][4] = {
      {10, 0, 2, 0.2023382},   {10 * std::cos(d), 10 * std::sin(d), 2, -0.9357813},
      {0, 0, 0, 0.2744834},    {2, 0, 2, 2.3525363},
      {0.5, 0, 2, -0.3914788}, {12, 0, 0, 0.4994402},
      {10, 0, 4.5, 0.2566991}, {12.8, 0, 4.5, 0.2450867},
      {12.8, 0, 0, -9.6300839}};
  for (const auto& p : pts)
    CHECK(value_at(f, p[0], p[1], p[2]) == Approx(p[3]).epsilon(0).margin(kPrinted));
  // the 24 blades: blade centres inside, mid-gaps outside, at r = 10, z = 2
  for (int k = 0; k < 24; ++k) {
    const double t = 2 * std::numbers::pi * k / 24;
    CHECK(value_at(f, 10 * std::cos(t), 10 * std::sin(t), 2) > 0);
    CHECK(value_at(f, 10 * std::cos(t + d), 10 * std::sin(t + d), 2) < 0);
  }
}

TEST_CASE("UAV (seed 000 Appendix B): digest T20 values", "[rf][model]") {
  const ImplicitFunction f = model("uav.rf");
  const double pts[][4] = {
      {0, 0, 0, 0.0163157},    {0, 1.2, 0, 0.0185213},   {0, 1.35, 0, -0.1817312},
      {0, 0, 1.2, -0.8812495}, {-3, 0, 0.3, -0.0985307}, {1, 1, 0, 0.0098262},
      {1, 0, -0.3, 0.0655055}, {4.9, 0, 0, 0.0097110},   {-4, 0, 0, -1.0450750}};
  for (const auto& p : pts)
    CHECK(value_at(f, p[0], p[1], p[2]) == Approx(p[3]).epsilon(0).margin(kPrinted));
  CHECK(value_at(f, -2, 1.5, 0) == Approx(0).epsilon(0).margin(1e-15)); // on the wing slab plane (T20 note)
  // the singular plane of the cone substitution (x = 3): finite values, body inside
  CHECK(value_at(f, 3, 0, 0) > 0);
  CHECK(std::isfinite(value_at(f, 3, 0.05, 0)));
  // blended fuselage component (T17): wp(0,0,0) = 1.3
  CHECK(value_at(model("uav.rf", "wp"), 0, 0, 0) == Approx(1.3).epsilon(0).margin(1e-15));
}

TEST_CASE("Car (seed 002): stage values of digest 002 §12.2", "[rf][model]") {
  const ImplicitFunction roof = model("car.rf", "f1"), trunk = model("car.rf", "f2");
  const ImplicitFunction hood = model("car.rf", "f3"), arches = model("car.rf", "w56");
  const double p6 = 5e-7; // digest 002 prints 6 decimals
  CHECK(value_at(roof, 0, 0, 4) == Approx(1).epsilon(0).margin(1e-15));
  CHECK(value_at(roof, 0, 0, 8) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(roof, 0, 8, 4) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(roof, 0, 0, 10) == Approx(-0.857493).epsilon(0).margin(p6));
  CHECK(value_at(roof, 0, 4, 6) == Approx(0.872872).epsilon(0).margin(p6));
  CHECK(test::gradient_at(roof, 0, 8, 4).norm() == Approx(1).epsilon(0).margin(1e-14));
  CHECK(test::gradient_at(roof, 0, 0, 8).norm() == Approx(1).epsilon(0).margin(1e-14));
  CHECK(value_at(trunk, 0, -10, 2) == Approx(1.848792).epsilon(0).margin(p6));
  CHECK(value_at(trunk, 0, -10, 6) == Approx(-1.146769).epsilon(0).margin(p6));
  CHECK(value_at(trunk, 0, 5, 2) == Approx(-10.977237).epsilon(0).margin(p6));
  CHECK(value_at(trunk, 0, -7.5, 0) == Approx(2.5).epsilon(0).margin(1e-15));
  CHECK(value_at(hood, 0, 10, 0) == Approx(2.202430).epsilon(0).margin(p6));
  CHECK(value_at(hood, 0, 10, 3.6) == Approx(-0.098125).epsilon(0).margin(p6));
  CHECK(value_at(hood, 0, 0.5, 1) == Approx(-0.542631).epsilon(0).margin(p6));
  CHECK(value_at(hood, 0, 17, 1) == Approx(0.479151).epsilon(0).margin(p6));
  CHECK(value_at(arches, 5, -6, 0) == Approx(-1.119135).epsilon(0).margin(p6));
  CHECK(value_at(arches, 0, -6, 0) == Approx(2.080334).epsilon(0).margin(p6));
  CHECK(value_at(arches, 5, 0, 0) == Approx(5.019396).epsilon(0).margin(p6));
  // one wheel at its centre: 2 - sqrt(1.4^2 + 0.6^2) = 0.4768455 (the digest prints 0.476829,
  // off in the 5th decimal from its own closed form)
  CHECK(value_at(model("car.rf", "f7"), 5, -6, 0) == Approx(2 - std::sqrt(2.32)).epsilon(0).margin(1e-15));
  const ImplicitFunction wheels = model("car.rf", "wheels");
  for (const auto& p :
       {Eigen::Vector3d(5, -6, 0), Eigen::Vector3d(5, 7, 0), Eigen::Vector3d(-5, -6, 0)})
    CHECK(value_at(wheels, p.x(), p.y(), p.z()) == Approx(0.480870).epsilon(0).margin(p6));
  const ImplicitFunction side = model("car.rf", "wb");
  CHECK(value_at(side, 7, 0, 2) == Approx(0.423203).epsilon(0).margin(p6));
  CHECK(value_at(side, 0, 0, 8) == Approx(3.031540).epsilon(0).margin(p6));
  CHECK(value_at(side, 5, 0, 8) == Approx(0).epsilon(0).margin(1e-14));
  CHECK(value_at(side, 6, 0, 5) == Approx(0).epsilon(0).margin(1e-14));
}

TEST_CASE("Car (seed 002): signs of the assembled stages, digest 002 §12.3", "[rf][model]") {
  const ImplicitFunction fig8a = model("car.rf"), fig5 = model("car.rf", "fig5");
  const ImplicitFunction body = model("car.rf", "body"), win = model("car.rf", "fig8b_windows");
  struct P {
    double x, y, z;
    int sign;
  };
  for (const P& p :
       {P{0, 0, 4, 1}, P{0, -10, 2, 1}, P{0, 10, 1, 1}, P{0, -6, 2.9, 1}, P{5, -6, 0.5, 1},
        P{5, 7, -1, 1}, P{5, -6, 2.9, -1}, P{7, 0, 2, 1}, P{8, 0, 2, -1}, P{0, 0, 8.5, -1},
        P{0, 0, -0.5, -1}, P{0, 19, 1, -1}, P{0, -16, 2, -1}}) {
    INFO(p.x << "," << p.y << "," << p.z);
    CHECK((value_at(fig8a, p.x, p.y, p.z) > 0 ? 1 : -1) == p.sign);
  }
  CHECK(value_at(fig5, 0, 0, 4) > 0);
  CHECK(value_at(fig5, 5, -6, 0.5) < 0); // arch cut before the wheels
  CHECK(value_at(body, 5, -6, 0.5) < 0);
  CHECK(value_at(fig5, 7, 0, 2) < 0); // x_s = 6 clips the bulge
  CHECK(value_at(body, 7, 0, 2) > 0);
  // windows, intended (recess) reading
  CHECK(value_at(win, 5.3, 3, 6) < 0);
  CHECK(value_at(win, 5.3, 0.2, 6) > 0);
  CHECK(value_at(win, 4.5, 3, 6) > 0);
  CHECK(value_at(win, 5.3, 3, 4.8) > 0);
  // Fig. 5b parameters (a1 = 9, y2 = 14, z2 = 4, c3 = 70): the trunk ends at y = -14
  const ImplicitFunction fig5b =
      model("car.rf", "fig5", {{"a1", 9}, {"y2", 14}, {"z2", 4}, {"c3", 70}});
  CHECK(value_at(fig5b, 0, -13.5, 2) > 0);
  CHECK(value_at(fig5b, 0, -14.5, 2) < 0);
  CHECK(value_at(fig5, 0, -14.5, 2) > 0); // the Fig. 5a trunk (y2 = 15) reaches it
}

TEST_CASE("NACA 0011 plate with holes (seed 003 §3.4): digest 003 §11.3 values", "[rf][model]") {
  const ImplicitFunction curve = model("naca0011_plate.rf", "profile");
  const ImplicitFunction plate = model("naca0011_plate.rf", "plate2d");
  const double p6 = 5e-7; // digest 003 prints 6 decimals
  const double pts[][4] = {
      {5, 0, 1.846134, 1.285666},    {10, 0, 2.182725, -0.668583}, {15, 0, 2.156375, 1.321376},
      {20, 0, 1.936481, -1.270976},  {22, 0, 1.810373, 0.600594},  {25, 0, 1.588569, -0.700239},
      {30, 0, 1.145801, 1.109839},   {35, 0, 0.625742, 0.621350},  {-1, 0, -1.000000, -1.023947},
      {20, 3, -1.058504, -1.285491}, {5, 1, 0.854460, 0.735228},   {38, 0, 0.277078, 0.276471}};
  for (const auto& p : pts) {
    INFO(p[0] << "," << p[1]);
    CHECK(value_at(curve, p[0], p[1], 0) == Approx(p[2]).epsilon(0).margin(p6));
    CHECK(value_at(plate, p[0], p[1], 0) == Approx(p[3]).epsilon(0).margin(p6));
  }
  // n = 100 per branch changes the values by < 1e-3: (5,0) -> 1.845450 / 1.285361
  CHECK(value_at(model("naca0011_plate.rf", "profile", {{"n", 100}}), 5, 0, 0) ==
        Approx(1.845450).epsilon(0).margin(p6));
  const ImplicitFunction f = model("naca0011_plate.rf");
  CHECK(value_at(f, 5, 0, 0.5) > 0);
  CHECK(value_at(f, 5, 0, 1.5) < 0); // beyond the plate's thickness
  CHECK(value_at(f, 20, 0, 0) < 0);  // in the round hole
}

TEST_CASE("Valve (seed 002 Fig. 2, reconstruction): inside and outside points", "[rf][model]") {
  const ImplicitFunction f = model("valve.rf");
  const double c = std::cos(std::numbers::pi / 16), s = std::sin(std::numbers::pi / 16);
  struct P {
    double x, y, z;
    int sign;
    const char* what;
  };
  for (const P& p : {P{2, 0, 0, 1, "body wall"}, P{0, 0, 0, -1, "axial bore"},
                     P{0, 0, 7.5, 1, "closed top of the neck"}, P{0, 0, 8.2, -1, "above"},
                     P{2.5, 0, 0.5, -1, "groove"}, P{2.8, 0, 3.4, -1, "slot"},
                     P{2.8 * c, 2.8 * s, 3.4, 1, "flange between slots"},
                     P{2.8, 0, 3.1, 1, "flange below the slots"},
                     P{1.85, 0, -3.5, -1, "beyond the hexagon's flat"},
                     P{1.85 * std::cos(std::numbers::pi / 6), 1.85 * std::sin(std::numbers::pi / 6),
                       -3.5, 1, "towards the hexagon's corner"},
                     P{0, 0, -3.5, -1, "bore through the nut"}, P{3.1, 0, 3.2, -1, "outside"}}) {
    INFO(p.what);
    CHECK((value_at(f, p.x, p.y, p.z) > 0 ? 1 : -1) == p.sign);
  }
}

TEST_CASE("Every shipped model parses, is finite on its box and has inside and outside",
          "[rf][model]") {
  for (const char* name : {"impeller.rf", "uav.rf", "car.rf", "valve.rf", "naca0011_plate.rf"}) {
    INFO(name);
    const ImplicitFunction f = model(name);
    REQUIRE(!f.box.isEmpty());
    const int n = 24;
    Points3 P(n * n * n, 3);
    for (int k = 0, r = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i, ++r)
          P.row(r) = f.box.min().transpose() +
                     (Eigen::Vector3d(i, j, k) / (n - 1)).cwiseProduct(f.box.sizes()).transpose();
    Eigen::VectorXd F(P.rows());
    f.value(P, F);
    CHECK(F.allFinite());
    CHECK(F.maxCoeff() > 0);
    // the body lies inside the box: F < 0 on all its faces
    for (Eigen::Index r = 0; r < P.rows(); ++r) {
      const Eigen::Vector3d p = P.row(r).transpose();
      const bool face =
          ((p - f.box.min()).array() == 0).any() || ((p - f.box.max()).array() == 0).any();
      if (face)
        CHECK(F(r) < 0);
    }
  }
}

TEST_CASE("Model language: operators, comments, functions, parameters", "[rf][language]") {
  auto v = [](const std::string& body, double x = 0, double y = 0, double z = 0,
              const ModelOptions& o = {}) {
    return value_at(parse_model(kBox + body, "m.rf", o), x, y, z);
  };
  CHECK(v("res = -2^2;") == -4); // unary minus binds looser than ^
  CHECK(v("res = 2^-1;") == 0.5);
  CHECK(v("res = 8/2/4 + 2*3 - 1;") == 6);        // left associative
  CHECK(v("res = x.*y + x.^2 ./ 2;", 2, 3) == 8); // MATLAB element-wise operators
  CHECK(v("% comment\n# comment\n// comment\nres = 1; % trailing\n") == 1);
  CHECK(v("res = .5 + 1e-1 + 2.5E+1 + 3.;") == Approx(28.6).epsilon(0).margin(1e-14));
  CHECK(v("def f(a, b) = a*b + x;\nres = f(2, 3);", 1) == 7);
  CHECK(v("k = 2;\ndef g(a) = a*k;\nk = 5;\nres = g(1) + k;") == 7); // definitions capture
  CHECK(v("a = 1; a = a + 1; res = a;") == 2);                       // reassignment
  CHECK(v("pi = 3; res = pi;") == 3);                                // pi can be shadowed
  CHECK(v("res = pi;") == std::numbers::pi);
  // n-ary R-operations fold from the left: and0(3, 4, 100) = and0(and0(3, 4), 100)
  CHECK(v("res = rfAND(3, 4) + and0(3, 4, 100) + rfNOT(1);") ==
        Approx(2 + (102 - std::sqrt(10004.0)) - 1).epsilon(0).margin(1e-13));
  CHECK(v("param r = 1;\nres = r;") == 1);
  ModelOptions o;
  o.parameters["r"] = 2.5;
  CHECK(v("param r = 1;\nres = r;", 0, 0, 0, o) == 2.5);
  o.output = "q";
  CHECK(v("param r = 1;\nq = 2*r; res = 0;", 0, 0, 0, o) == 5);
  // BOM and CRLF line ends
  CHECK(value_at(parse_model("\xEF\xBB\xBF"
                             "box(0,0,0,1,1,1);\r\nres = 3;\r\n"),
                 0, 0) == 3);
  CHECK(value_at(parse_model(kBox + "res = polygon_region(x, y, [0,0, 2,0, 2,2, 0,2]);"), 1, 0.5) ==
        Approx(0.5).epsilon(0).margin(1e-15));
}

TEST_CASE("Model language: one InputError with FILE:LINE:COLUMN per mistake", "[rf][language]") {
  struct Case {
    std::string text, message;
  };
  const Case cases[] = {
      {kBox + "res = 1 +;", "m.rf:2:10: expected a number, a name, '(' or '[', found ';'"},
      {kBox + "res = 1",
       "m.rf:2:8: expected ';' at the end of the statement, found the end of the file"},
      {kBox + "res = (1 + 2;", "m.rf:2:13: expected ')' to close '(' at 2:7, found ';'"},
      {kBox + "res = sqr(x);", "m.rf:2:7: unknown function 'sqr' (did you mean 'sqrt'?)"},
      {kBox + "radius = 1;\nres = radiu;",
       "m.rf:3:7: unknown variable 'radiu' (did you mean 'radius'?)"},
      {kBox + "res = sin(x, y);", "m.rf:2:7: sin expects 1 argument(s), got 2"},
      {kBox + "res = and0(x);", "m.rf:2:7: and0 expects at least 2 argument(s), got 1"},
      {kBox + "res = sphere(x, y, z, -1);", "m.rf:2:7: sphere: the radius R must be > 0, got -1"},
      {kBox + "res = fold_x(x, y);", "m.rf:2:17: fold_x: argument 2 must be a constant"},
      {kBox + "res = mu_fourier(x, 2, 2.5);",
       "m.rf:2:24: mu_fourier: argument 3 must be an integer from 1 to 1000, got 2.5"},
      {kBox + "res = x^2^3;", "m.rf:2:10: a^b^c is ambiguous"},
      {kBox + "res = x^-2^3;", "m.rf:2:11: a^b^c is ambiguous"},
      {kBox + "res = 1 @ 2;", "m.rf:2:9: unexpected character '@'"},
      {kBox + "res = 1e999;", "m.rf:2:7: number 1e999 is out of the range of a double"},
      {kBox + "res = 2x;", "m.rf:2:7: malformed number '2x'"},
      {kBox + "x = 1; res = x;", "m.rf:2:1: cannot assign to the coordinate 'x'"},
      {kBox + "res = sin;", "m.rf:2:7: 'sin' is a function; call it as sin(...)"},
      {kBox + "a = 1; res = a(2);", "m.rf:2:14: 'a' is a variable, not a function"},
      {kBox + "res = [1, 2];", "m.rf:2:7: a list cannot be assigned to a variable"},
      {kBox + "res = 1 + [1, 2];",
       "m.rf:2:11: a list [...] can only be an argument of polygon_region"},
      {kBox + "def sin(a) = a;", "m.rf:2:1: 'sin' is a built-in function and cannot be redefined"},
      {kBox + "def f(a, a) = a;", "m.rf:2:10: parameter 'a' appears twice"},
      {kBox + "def f(a) = a; res = f(1, 2);", "m.rf:2:21: f expects 1 argument(s), got 2"},
      {kBox + "param r = x; res = r;",
       "m.rf:2:11: the default of parameter 'r' must be a constant"},
      {kBox + "box(0,0,0,1,1,1); res = 1;", "m.rf:2:1: box declared twice (first at line 1)"},
      {"box(0, 0, 0, 1, -1, 1); res = 1;",
       "m.rf:1:17: box: the upper y bound (-1) must exceed the lower (0)"},
      {"box(0, 0, x, 1, 1, 1); res = 1;", "m.rf:1:11: box bounds must be finite constants"},
      {"res = 1;", "m.rf: the model has no box statement"},
      {kBox + "r = 1;", "m.rf: the model does not assign the output variable 'res'"},
      {kBox + "res = polygon_region(x, y, [0, 0, 1]);",
       "m.rf:2:28: polygon_region: the list has 3 numbers"},
      {kBox + "res = polygon_region(x, y, [0, 0, 1, 0, 2, 0, x]);",
       "m.rf:2:47: list entries must be finite constants"},
      {kBox + "res = 1;\n\xC3\xA9", "m.rf:3:1: unexpected byte 0xC3"},
      {kBox + "1 = 2;", "m.rf:2:1: expected a statement"},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    CHECK_THAT(error_of(c.text), Catch::StartsWith(c.message));
  }
  // graph passes recurse along operand chains: a chain longer than 20000 is refused, not a crash
  std::string deep = kBox + "a = x;\n";
  for (int i = 0; i < 25000; ++i)
    deep += "a = a + y;\n";
  CHECK_THAT(error_of(deep + "res = a;"),
             Catch::StartsWith("m.rf:20003:1: expression too deep: more than 20000 nested"));
  ModelOptions o;
  o.parameters["rr"] = 1;
  CHECK_THAT(error_of(kBox + "param r = 1; res = r;", o),
             Catch::StartsWith("m.rf: parameter 'rr' is not declared by a 'param' statement in the "
                               "model (did you mean 'r'?)"));
  try {
    load_model("/nonexistent/dir/model.rf");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("/nonexistent/dir/model.rf: cannot open: "));
  }
}

TEST_CASE("The examples of docs/formats.md behave as described", "[rf][language]") {
  const ImplicitFunction holed = parse_model(R"(
box(-1.2, -1.2, -1.2, 1.2, 1.2, 1.2);
param r = 0.4;
ball = sphere(x, y, z, 1);
hole = circle(x, y, r);
res = and_fillet(ball, -hole, 0.1);
)");
  CHECK(value_at(holed, 0.7, 0, 0) > 0);  // in the ball, beyond the hole
  CHECK(value_at(holed, 0, 0, 0) < 0);    // in the hole
  CHECK(value_at(holed, 0, 0, 0.95) < 0); // the hole runs through
  const ImplicitFunction plate = parse_model(R"(
box(-2, -1.5, -0.2, 14, 1.5, 0.2);
plate = and0(rectangle(x - 6, y, 8, 1), strip(z, 0.1));
holes = fold_x_finite(circle(x, y, 0.5), 3, 12);
res = sub0(plate, holes);
)");
  for (int k = 0; k <= 4; ++k) {
    CHECK(value_at(plate, 3.0 * k, 0, 0) < 0);       // a hole
    CHECK(value_at(plate, 3.0 * k + 1.5, 0, 0) > 0); // plate between holes
  }
  CHECK(value_at(plate, -1.5, 0, 0) > 0); // no hole before the first
  const ImplicitFunction twisted = parse_model(R"(
box(-2, -2, -1, 2, 2, 4);
bar = twist_z(rectangle(x, y, 0.8, 0.2), 0.5 * z);
vase = revolve_z(circle(x - 1, y - 1.5, 0.8));
res = or0(and0(bar, layer(z, 0, 3)), vase);
)");
  CHECK(value_at(twisted, 0.7, 0, 0.1) > 0); // the bar near its base lies along x
  CHECK(value_at(twisted, 0, 0.7, 0.1) < 0);
  const double t = 0.5 * 2.5; // at z = 2.5 it has turned by 1.25 rad
  CHECK(value_at(twisted, 0.7 * std::cos(t), 0.7 * std::sin(t), 2.5) > 0);
  CHECK(value_at(twisted, 1, 0, 1.5) > 0); // the torus tube at radius 1, height 1.5
}
