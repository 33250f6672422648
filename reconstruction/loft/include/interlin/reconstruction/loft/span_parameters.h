#pragma once
// Spanwise parameters of a stack of sections: where the section lines v = v_k of the loft sit
// (seed 001 §2.5: the surface is interlineated between the lines v = v_k). Either the sections'
// own stations along the stacking direction, or a spacing from the distance between
// neighbouring section curves (chord length and its powers).

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace interlin {

// How the parameters v_k are spaced.
//   automatic    chosen by leave-one-out cross-validation (span_model.h)
//   station      the sections' stations (section_stations): planar sections at the distance of
//                their planes along the common normal, sections on coaxial surfaces of
//                revolution (turbomachine stream surfaces) at their meridional position
//   chord        the mean distance between neighbouring section curves
//   centripetal  its square root
//   uniform      equal steps
enum class SpanParameters { automatic, station, chord, centripetal, uniform };

// "auto", "station", "chord", "centripetal", "uniform".
std::string to_string(SpanParameters p);

// What a section's station measures.
//   none                 no stacking detected: neither criterion below holds
//   parallel_planes      each section lies across a plane, the planes parallel (common normal)
//   coaxial_revolution   each section lies on a surface of revolution about the z axis
//                        (x = R cos t, y = R sin t), like the stream surfaces of a turbomachine
enum class Stacking { none, parallel_planes, coaxial_revolution };

// "none", "parallel planes", "coaxial surfaces of revolution about z".
std::string to_string(Stacking s);

// The stations of a stack.
//   stacking  what was detected
//   station   K strictly increasing stations (empty for none): parallel planes, the position of
//             each section's plane along the common normal (oriented from the first section to
//             the last); coaxial revolution, the meridional position of each section's stream
//             surface: its offset across the common flow direction of the meridional plane
//             (z, R), at one reference point along it (for cylinders the radius)
//   normal    parallel planes: the common unit normal
//   spread    the test's measure for the detected stacking (for none: of the closer candidate):
//             the largest width of a section across its stacking surface divided by the
//             smallest gap between neighbouring stations (<= kStationSpread when detected)
struct SectionStations {
  Stacking stacking = Stacking::none;
  Eigen::VectorXd station;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double spread = std::numeric_limits<double>::infinity();
};

// The criterion shared by both stackings: a section is "at" one station when its own width
// across the stacking surface (planes: its extent along the common normal; revolution: the
// distance in the meridional plane (z, R) between its two sides) is at most 1 % of the smallest
// gap between neighbouring stations. Then the station locates the whole section to 1 % of the
// spacing, which is what the spanwise interpolation needs; design data (CAD planes, the NASA
// stream-surface tables) meet it to round-off, and a warped stack misses it by orders of
// magnitude (Rotor 37 as planes: spread 6, see docs/design.md).
inline constexpr double kStationSpread = 0.01;

// Inputs: K >= 2 closed sections (#P_k by 3 each), in stacking order.
// Output: the stacking whose criterion holds with the smaller spread (parallel planes on a tie:
// planes z = const are surfaces of revolution about z too), else none. Stations must increase
// strictly from the first section to the last.
SectionStations section_stations(const std::vector<Eigen::MatrixXd>& sections);

// The spanwise parameters v (K values, v(0) = 0, v(K-1) = 1, increasing).
// Inputs:
//   p         station, chord, centripetal or uniform (not automatic)
//   distance  K-1 mean distances between neighbouring section curves (> 0)
//   station   K stations (used for p = station; must then be given)
// Throws std::invalid_argument for automatic, or station without stations.
Eigen::VectorXd span_parameters(SpanParameters p, const Eigen::VectorXd& distance,
                                const Eigen::VectorXd& station);

} // namespace interlin
