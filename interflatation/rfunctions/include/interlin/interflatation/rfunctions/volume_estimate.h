#pragma once
// The volume of a body {F > 0} by stratified Monte Carlo: an independent check of mesh volumes
// (seed 000 T19/T21 quote Monte Carlo volumes for the impeller and the UAV).

#include "interlin/interflatation/implicit_function.h"

namespace interlin {

struct VolumeEstimate {
  double volume = 0;         // estimate of vol{F > 0} inside f.box
  double standard_error = 0; // its estimated standard deviation
  long samples = 0;          // evaluations of F
};

// Inputs:
//   f        the body; f.box must hold it (F <= 0 outside the box is assumed, not checked)
//   cell     target edge of the strata: the box is cut into ceil(size / cell) cells per axis
//   seed     random seed (the estimate depends on the seed only, not on the thread count)
//   threads  evaluation threads (>= 1), each on whole layers of cells
// Output: two independent uniform points per cell; volume = sum over cells of the cell volume
//   times the fraction of the two inside; standard_error from the pairs (each cell contributes
//   cellvol^2 (i1 - i2)^2 / 4, the unbiased variance estimate with two samples per stratum). Only
//   cells cut by the surface contribute variance, so the error falls like cell^(1/2) times the
//   surface area, far below plain Monte Carlo with the same samples.
// Throws std::invalid_argument for an empty box, cell <= 0, more than 2^31 cells or threads < 1.
VolumeEstimate estimate_volume(const ImplicitFunction& f, double cell, unsigned seed,
                               int threads = 1);

} // namespace interlin
