#pragma once
// Sectioned scans (CMM or laser-line scans of blades): points near a family of parallel planes or
// of coaxial cylinders, each slice a closed profile. Detects the family and splits the points
// into slices. See also: fit_sliced_scan (profiles -> fitted sections -> loft).

#include <Eigen/Core>
#include <vector>

namespace interlin {

// automatic: try planar, then radial (detect_slices); none: not a sectioned scan.
enum class SliceKind { automatic, planar, radial, none };

// The station s(p) is constant on each slice:
//   planar  s = axis . p                      (planes normal to axis)
//   radial  s = |p - (axis . p) axis|          (cylinders about the line through the origin
//                                               along axis, the machine axis of a rotor)
//   stations  K increasing: the mean station of each slice
//   members   K lists of point rows, one per slice
//   spread    rms of s(p) - station over all points: the noise normal to the slices
struct SliceFamily {
  SliceKind kind = SliceKind::none;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  std::vector<double> stations;
  std::vector<std::vector<Eigen::Index>> members;
  double spread = 0;
  double station(const Eigen::Vector3d& p) const;
};

// Finds the family: for each candidate axis (planar: the coordinate axes and the points'
// principal axes; radial: the coordinate axes), the sorted stations split where a gap is at
// least kSliceGapRatio times every gap kept inside the slices, then a slice whose spread exceeds
// 2.5 times the median slice's (two close slices of an unevenly spaced scan merged) split at the
// valleys of its density (else, when the gaps find no family, all stations split at the valleys
// of their density, for noisy slices); the family is accepted when it has
// >= 3 slices of >= kMinSlicePoints points, each slice's station spread is at most a quarter of
// the slice spacing, and each slice extends across at least 10 times its spread (a profile, not
// a block). The accepted candidate with the thinnest slices (spacing / spread) wins; a planar
// family's normal is then refined to the one that fits all slices best (least squares).
// Inputs: P #P by 3; kind automatic, planar or radial.
// Output: the family, kind none when no candidate passes.
SliceFamily detect_slices(const Eigen::MatrixX3d& P, SliceKind kind = SliceKind::automatic);

// Orders the points of one closed, airfoil-like profile (P #P by 2, in its slice's plane) around
// it: both sides are graphs over the longest chord, split by the mean line (midpoints of the
// extreme offsets in bins along the chord, from the bins that hold both sides: offset range at
// least half the median), and each nose (the last 10 % of the chord at either
// end) is star-shaped from the mean line's point where it starts. Output: #P row indices, around
// the profile (one side by increasing chord position, the other by decreasing position, the
// noses by angle).
std::vector<Eigen::Index> order_profile(const Eigen::MatrixX2d& P);

} // namespace interlin
