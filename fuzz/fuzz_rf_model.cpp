// Fuzz target: R-function model files (.rf), interflatation/rfunctions: parsing, evaluation of
// the statements into an expression, compilation, and the compiled program's value and gradient
// at the corners and centre of the model's box.
#include "fuzz_support.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/rfunctions/model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    const ImplicitFunction f = parse_model(fuzz::text(data, size), "fuzz.rf");
    Points3 P(3, 3);
    P.row(0) = f.box.min().transpose();
    P.row(1) = f.box.center().transpose();
    P.row(2) = f.box.max().transpose();
    Eigen::VectorXd F(3);
    Points3 G(3, 3);
    f.value(P, F);
    if (f.gradient)
      f.gradient(P, F, G);
  });
  return 0;
}
