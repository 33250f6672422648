#pragma once
// Point-cloud implicits in .ifl files (docs/formats.md, "Implicit model files", kinds cloud_pu and
// cloud_hrbf): the fitted partition of unity (cloud_implicit.h) or Hermite RBF (hermite_rbf.h)
// stored whole, so that a model read back evaluates to the same doubles as the one fitted.

#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/hermite_rbf.h"

namespace interlin {

// The .ifl block (kind cloud_pu, name model) of a fitted model. `noise` (the sigma the fit used)
// is stored for the record. Throws std::invalid_argument for non-finite values.
IflBlock to_ifl(const CloudImplicit& m, double noise);

// The model of a cloud_pu block. Throws InputError (block.fail) for a block that breaks the
// kind's rules: missing or mis-shaped arrays, non-finite values, sheet counts other than 1 or 2,
// frames that are not orthonormal. (The tiling of the root cube by the leaves is checked by
// cloud_implicit_function; the registered loader turns its error into the block's InputError.)
CloudImplicit cloud_implicit_from_ifl(const IflBlock& b);

// The .ifl block (kind cloud_hrbf, name model) of a Hermite RBF interpolant: its centres and
// coefficients as fitted (17 significant digits: the same doubles back).
IflBlock to_ifl(const HermiteRbf& m);

// The interpolant of a cloud_hrbf block. Throws InputError (block.fail) for missing or mis-shaped
// arrays, fewer than 4 centres, non-finite values, scale <= 0.
HermiteRbf hermite_rbf_from_ifl(const IflBlock& b);

// Registers the kinds cloud_pu and cloud_hrbf with load_ifl / load_implicit (ifl_registry.h).
// Idempotent and thread-safe; programs that read .ifl files call it once before (the interlin
// executable does).
void register_cloud_ifl_kind();

} // namespace interlin
