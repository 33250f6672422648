// The .ifl container: exact round trip, one-line errors for every kind of damage, the kind
// registry and the shared model loader.
#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/load_implicit.h"
#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/interflatation/rfunctions/expression.h"
#include "interlin/interflatation/rfunctions/primitives.h"
#include "support/test_support.h"

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

using namespace interlin;
using namespace std::string_literals;

namespace {

IflBlock sample_block() {
  IflBlock b;
  b.kind = "test_kind";
  b.name = "model";
  b.set("version", 1);
  b.set("third", 1.0 / 3);
  b.set("tiny", 4.9406564584124654e-324); // the smallest subnormal double
  b.set_text("source", "line one\nline two with \"quotes\" and \0 zero"s);
  b.set_text("empty", "");
  b.set_f64("values", {2, 3}, {0.1, -2.5, 1e300, -1e-300, M_PI, -0.0});
  b.set_i64("counts", {4}, {0, -1, std::numeric_limits<std::int64_t>::max(), 7});
  b.set_f64("none", {0}, {});
  IflBlock sub;
  sub.kind = "inner";
  sub.name = "child";
  sub.set("x", 2);
  sub.set_f64("newlines", {3}, {std::bit_cast<double>(std::uint64_t{0x0a0a0a0a0a0a0a0a}), 1, 2});
  b.blocks.push_back(sub);
  return b;
}

std::string text_of(const IflBlock& b) {
  std::ostringstream out;
  write_ifl(out, b);
  return out.str();
}

// The InputError message of parsing `text`.
std::string error_of(const std::string& text) {
  try {
    parse_ifl(text, "bad.ifl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST_CASE("ifl: every field reads back bit for bit", "[ifl]") {
  const IflBlock a = sample_block();
  const std::string text = text_of(a);
  CHECK(text.rfind("interlin-ifl 1\nblock test_kind model\n", 0) == 0);
  const IflBlock b = parse_ifl(text, "x.ifl");
  CHECK(b.kind == a.kind);
  CHECK(b.name == a.name);
  CHECK(b.numbers == a.numbers);
  CHECK(b.texts == a.texts);
  for (const auto& [name, arr] : a.arrays) {
    const IflArray& c = b.array(name);
    CHECK(c.dims == arr.dims);
    CHECK(c.i64 == arr.i64);
    REQUIRE(c.f64.size() == arr.f64.size());
    for (size_t k = 0; k < c.f64.size(); ++k)
      CHECK(std::bit_cast<std::uint64_t>(c.f64[k]) == std::bit_cast<std::uint64_t>(arr.f64[k]));
  }
  REQUIRE(b.blocks.size() == 1);
  CHECK(b.block("child").number("x") == 2);
  CHECK(b.block("child").f64("newlines", {3})[2] == 2);
  CHECK(text_of(b) == text); // and writes back identically
}

TEST_CASE("ifl: checked access names the block, field and shape", "[ifl]") {
  const IflBlock b = parse_ifl(text_of(sample_block()), "x.ifl");
  auto message = [&](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message([&] { b.number("missing"); }) ==
        "x.ifl:2: block test_kind model: missing number 'missing'");
  CHECK(message([&] {
          b.f64("values", {3, 2});
        }) == "x.ifl:2: block test_kind model: array 'values' must be 3 x 2, got 2 x 3");
  CHECK(message([&] { b.i64("values", {-1}); }) ==
        "x.ifl:2: block test_kind model: array 'values' must be i64");
  CHECK(message([&] { b.integer("third", 0, 5); }).find("must be an integer from 0 to 5") !=
        std::string::npos);
  CHECK(message([&] { b.block("nope"); }) ==
        "x.ifl:2: block test_kind model: missing block 'nope'");
}

TEST_CASE("ifl: damaged files give one line naming file and line", "[ifl]") {
  const std::string good = text_of(sample_block());
  CHECK(error_of("") ==
        "bad.ifl:1: unexpected end of file; expected the header line 'interlin-ifl 1'");
  CHECK(error_of("solid ascii\n").find("bad.ifl:1: not an interlin implicit model file") == 0);
  CHECK(error_of("interlin-ifl 2\n").find("bad.ifl:1: container version 2 is newer") == 0);
  CHECK(error_of("interlin-ifl x\n").find("bad.ifl:1: version: 'x' is not an integer") == 0);
  CHECK(error_of("interlin-ifl 1\nblock a b\nnumber n nan\nend\n").find("bad.ifl:3: number n") ==
        0);
  CHECK(error_of("interlin-ifl 1\nblock a b\nnumber n 1\nnumber n 2\nend\n")
            .find("bad.ifl:4: block a b: 'n' appears twice") == 0);
  CHECK(error_of("interlin-ifl 1\nblock a b\nfrobnicate\nend\n")
            .find("bad.ifl:3: unknown keyword 'frobnicate'") == 0);
  CHECK(error_of("interlin-ifl 1\nblock a b\nnumber n 1\n")
            .find("bad.ifl:4: unexpected end of file") == 0); // the missing line
  CHECK(error_of("interlin-ifl 1\nblock a b\nend\nend\n") ==
        "bad.ifl:3: unexpected data after the model block");
  CHECK(error_of("interlin-ifl 1\nblock a b/c\nend\n").find("is not a valid name") !=
        std::string::npos);
  CHECK(error_of("interlin-ifl 1\nblock a b\narray v f64 1000000000 1000000000\nend\n")
            .find("bad.ifl:3: array v: the file ends before its data") == 0);
  CHECK(error_of("interlin-ifl 1\nblock a b\narray v f32 1\n12345678\nend\n")
            .find("unknown type 'f32'") != std::string::npos);
  CHECK(error_of("interlin-ifl 1\nblock a b\ntext t 100\nshort\nend\n")
            .find("bad.ifl:3: text t: the file ends before its 100 bytes") == 0);
  std::string deep = "interlin-ifl 1\n";
  for (int i = 0; i < 10; ++i)
    deep += "block a b" + std::to_string(i) + "\n";
  CHECK(error_of(deep).find("nested deeper than 8") != std::string::npos);
  // Every truncation of a valid file is an error, never a crash or a silent partial model.
  for (size_t n = 0; n + 1 < good.size(); n += 7)
    CHECK(error_of(good.substr(0, n)).rfind("bad.ifl:", 0) == 0);
}

TEST_CASE("ifl: kinds come from the registry, unknown kinds are named", "[ifl]") {
  const std::vector<std::string> kinds = ifl_kinds();
  CHECK(std::count(kinds.begin(), kinds.end(), "section_body") == 1);
  CHECK(std::count(kinds.begin(), kinds.end(), "normalized_rf") == 1);
  IflBlock b;
  b.kind = "test_sphere";
  b.name = "model";
  b.set("radius", 2);
  CHECK_THROWS_WITH(
      load_ifl_model(b, "s.ifl"),
      Catch::StartsWith("<ifl>:0: block test_sphere model: unknown model kind (known: "));
  register_ifl_kind("test_sphere", [](const IflBlock& m, const std::string&) {
    const double r = m.number("radius");
    const rf::Expr x = rf::Expr::x(), y = rf::Expr::y(), z = rf::Expr::z();
    return rf::compile(rf::sphere(x, y, z, r), Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-r),
                                                                   Eigen::Vector3d::Constant(r)));
  });
  CHECK_THROWS_AS(register_ifl_kind("test_sphere", nullptr), std::invalid_argument);
  CHECK_THROWS_AS(register_ifl_kind("bad name", nullptr), std::invalid_argument);
  test::TempDir d("ifl");
  {
    std::ofstream out(d / "s.ifl", std::ios::binary);
    write_ifl(out, b);
  }
  // The shared loader picks the kind by extension: .ifl here, .rf below.
  const ImplicitFunction f = load_implicit(d / "s.ifl");
  Points3 P(2, 3);
  P << 0, 0, 0, 3, 0, 0;
  Eigen::VectorXd F(2);
  f.value(P, F);
  CHECK(F(0) > 0);
  CHECK(F(1) < 0);
  CHECK_THROWS_AS(load_implicit(d / "s.ifl", ModelOptions{"other", {}}), std::invalid_argument);
  CHECK_THROWS_WITH(load_implicit(d / "s.stl"), Catch::Contains("unknown model type '.stl'"));
  CHECK_THROWS_AS(load_implicit(d / "missing.ifl"), InputError);
  CHECK(is_implicit_model("A.IFL"));
  CHECK(is_implicit_model("a.rf"));
  CHECK_FALSE(is_implicit_model("a.csv"));
}

TEST_CASE("ifl: .rf models use .ifl bodies as operands, moved and differentiated", "[ifl][rf]") {
  test::TempDir d("iflrf");
  IflBlock b;
  b.kind = "test_ball";
  b.name = "model";
  register_ifl_kind("test_ball", [](const IflBlock&, const std::string&) {
    const rf::Expr x = rf::Expr::x(), y = rf::Expr::y(), z = rf::Expr::z();
    return rf::compile(rf::sphere(x, y, z, 1.0), Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1),
                                                                     Eigen::Vector3d::Constant(1)));
  });
  {
    std::ofstream out(d / "ball.ifl", std::ios::binary);
    write_ifl(out, b);
  }
  {
    std::ofstream out(d / "two.rf");
    out << "box(-3, -2, -2, 3, 2, 2);\n"
           "b = ifl(\"ball.ifl\");\n"
           "res = or0(translate(b, -1.5, 0, 0), translate(b, 1.5, 0, 0));\n";
  }
  const ImplicitFunction f = load_implicit(d / "two.rf");
  const ImplicitFunction ball =
      rf::compile(rf::sphere(rf::Expr::x(), rf::Expr::y(), rf::Expr::z(), 1.0), f.box);
  Points3 P(4, 3);
  P << -1.5, 0.3, 0, 1.5, 0, -0.2, 0, 0, 0, 1.2, 0.4, 0.1;
  Eigen::VectorXd F(4), B(4);
  Points3 G(4, 3), GB(4, 3);
  f.gradient(P, F, G);
  // At (-1.5, 0.3, 0) the left ball dominates: compare with the ball itself moved.
  Points3 Q = P;
  Q.col(0).array() += 1.5;
  ball.gradient(Q, B, GB);
  CHECK(F(0) > 0);
  CHECK(F(1) > 0);
  CHECK(F(2) < 0);
  // The R-disjunction of the two copies, from their values and gradients.
  Points3 L = P, R = P;
  L.col(0).array() += 1.5;
  R.col(0).array() -= 1.5;
  Eigen::VectorXd a(4), c(4);
  Points3 ga(4, 3), gc(4, 3);
  ball.gradient(L, a, ga);
  ball.gradient(R, c, gc);
  for (int i = 0; i < 4; ++i) {
    const double h = std::hypot(a(i), c(i));
    CHECK(F(i) == Approx(a(i) + c(i) + h).epsilon(1e-14));
    const Eigen::RowVector3d g = ga.row(i) + gc.row(i) + (a(i) * ga.row(i) + c(i) * gc.row(i)) / h;
    CHECK((G.row(i) - g).norm() <= 1e-12);
  }
  // Errors in the operand: the .rf position, then the .ifl file's own line.
  {
    std::ofstream out(d / "bad.rf");
    out << "box(-1, -1, -1, 1, 1, 1);\nres = ifl(\"missing.ifl\");\n";
  }
  CHECK_THROWS_WITH(load_implicit(d / "bad.rf"), Catch::Contains("bad.rf:2:11: ifl: ") &&
                                                     Catch::Contains("missing.ifl: cannot open"));
  {
    std::ofstream out(d / "bad2.rf");
    out << "box(-1, -1, -1, 1, 1, 1);\nres = ifl(2);\n";
  }
  CHECK_THROWS_WITH(load_implicit(d / "bad2.rf"),
                    Catch::Contains("bad2.rf:2:11: ifl: argument 1 must be a file name"));
  {
    std::ofstream out(d / "bad3.rf");
    out << "box(-1, -1, -1, 1, 1, 1);\nres = sqrt(\"ball.ifl\");\n";
  }
  CHECK_THROWS_WITH(load_implicit(d / "bad3.rf"),
                    Catch::Contains("bad3.rf:2:12: sqrt: argument 1 is a text"));
  {
    std::ofstream out(d / "bad4.rf");
    out << "box(-1, -1, -1, 1, 1, 1);\nres = ifl(\"ball.ifl);\n";
  }
  CHECK_THROWS_WITH(load_implicit(d / "bad4.rf"),
                    Catch::Contains("bad4.rf:2:11: unterminated text"));
}
