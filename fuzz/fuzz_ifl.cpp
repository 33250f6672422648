// Fuzz target: implicit model files (.ifl), interflatation/models: the container (parse_ifl),
// the model kind's loader (load_ifl_model: section bodies, normalised R-function models, point
// clouds' partitions of unity), and
// the function's value and gradient at the corners and centre of the model's box and at a point
// outside it. A section body's values must be finite inside its box (its far field is a
// tricubic of finite node values; an R-function source may be undefined anywhere, as in rf_model).
#include "fuzz_support.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  register_cloud_ifl_kind(); // as the CLI does (tools/interlin.cpp); idempotent
  fuzz::only_throws<InputError>([&] {
    const IflBlock model = parse_ifl(fuzz::text(data, size), "fuzz.ifl");
    const ImplicitFunction f = load_ifl_model(model, "fuzz.ifl");
    Points3 P(4, 3);
    P.row(0) = f.box.min().transpose();
    P.row(1) = f.box.center().transpose();
    P.row(2) = f.box.max().transpose();
    P.row(3) = (f.box.max() + f.box.sizes()).transpose();
    Eigen::VectorXd F(4);
    Points3 G(4, 3);
    f.value(P, F);
    if (model.kind == "section_body" && !F.head(3).allFinite())
      std::abort();
    if (f.gradient)
      f.gradient(P, F, G);
  });
  return 0;
}
