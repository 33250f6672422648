#pragma once
// Shaded PNG preview of a triangle mesh: a small deterministic software rasteriser (orthographic
// 3/4 view, z-buffer, smooth two-sided shading, supersampled anti-aliasing) with optional dark
// polylines (e.g. the input section curves) drawn on top. No GUI, no display, no VTK.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace interlin {

struct PreviewOptions {
  // Output size in pixels, each in [1, 16384].
  int width = 1200, height = 900;
  // Camera "up" direction in model space (any length; for a blade, the spanwise direction). The
  // zero vector means automatic: the largest principal axis of V, signed so that its
  // largest-magnitude component is positive.
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  // 3/4 view around `up`: the camera sits elevation_deg above the plane orthogonal to `up`, at
  // azimuth_deg (right-handed about `up`) from the model's own horizontal axis: the principal axis
  // of V projected onto that plane (for a blade, about the mean chord), so the view turns with the
  // model; without a distinct one (e.g. a sphere), the coordinate axis least aligned with `up`.
  double azimuth_deg = 45, elevation_deg = 25;
  // Anti-aliasing: render supersample x supersample times larger and box-filter down; in [1, 8].
  // width * height * supersample^2 must not exceed 2^26 sub-pixels.
  int supersample = 2;
  // Background: vertical linear gradient from the top row to the bottom row, RGB in [0, 1].
  Eigen::Vector3d background_top{0.97, 0.975, 0.98}, background_bottom{0.80, 0.83, 0.86};
};

// RGB image, row-major from the top row, 3 bytes per pixel: rgb.size() == 3 * width * height.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

// Renders the triangle mesh with an orthographic 3/4 view and returns the image.
// All rows of V and the polylines together are fitted (bounding box in the view plane) to 85 % of
// the frame and centred. Hidden surfaces: z-buffer on a supersampled grid. Shading: one metallic
// blue-grey material, per-pixel interpolated normals (area-weighted over the faces around each
// vertex, faces bending away by more than 60 degrees excluded so that sharp edges stay crisp),
// two-sided (each triangle shows the side facing the camera); lights fixed to the camera: a key
// light from the upper left, a weaker fill from the right, a headlight, sky/ground ambient and a
// Fresnel-weighted reflection of a simple studio. Computed in linear light, written as sRGB.
// Polylines are dark lines 1.5 output pixels wide, depth-tested against the mesh with a small
// bias, so curves lying on the surface stay visible while curves behind it are hidden.
// Inputs:
//   V          #V by 3 vertex positions
//   F          #F by 3 vertex indices into V (any orientation)
//   polylines  each #P by 3, drawn open (repeat the first point to close a curve); a single
//              point draws a dot, an empty matrix is skipped
//   options    see PreviewOptions
// Output: options.width by options.height image. Deterministic: same input, same bytes.
// Speed: a 200k-triangle mesh at 1200 x 900, supersample 2, renders in about 0.1 s (-O2).
// Throws std::invalid_argument for an empty mesh, wrong column counts, out-of-range indices,
// non-finite (or overflowing) coordinates or bad options (size, supersample, angles, up vector,
// background).
Image render_preview(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                     const std::vector<Eigen::MatrixXd>& polylines, const PreviewOptions& options);

// Writes `image` as an 8-bit RGB PNG (libpng), atomically: the file appears whole or not at all.
// Throws std::invalid_argument when the image size does not match its pixel buffer and
// std::runtime_error("cannot write PATH: reason") when the file cannot be written.
void write_png(const std::string& path, const Image& image);

// render_preview followed by write_png.
void write_preview_png(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       const std::vector<Eigen::MatrixXd>& polylines = {},
                       const PreviewOptions& options = {});

} // namespace interlin
