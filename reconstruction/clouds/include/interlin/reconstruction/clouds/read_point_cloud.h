#pragma once
// Point-cloud files: .pcd (PCL, ascii / binary / binary_compressed), .ply (ascii / binary, the
// vertex element), .xyz / .xyzn / .txt (whitespace-separated x y z [nx ny nz ...]) and .csv (a
// header naming x, y, z and optionally nx, ny, nz). Formats and errors: docs/formats.md,
// "Point clouds".

#include "interlin/reconstruction/clouds/point_cloud.h"

#include <string>
#include <string_view>
#include <vector>

namespace interlin {

// Reads the cloud in `path`, the format chosen by the extension (case-insensitive).
// Headers and ASCII data are parsed strictly (every line checked, numbers as in section files);
// binary payloads are checked against the header before anything is allocated, so memory stays
// proportional to the file (PCD binary_compressed blocks are decompressed by PCL's LZF codec).
// Inputs:
//   path   the file; named in messages
// Outputs:
//   the cloud (normals when the file has all three normal fields; they are normalised, and
//   dropped with a note when one is zero or not finite); `notes` (optional) receives one line per
//   thing the reader decided (skipped invalid points of organised PCD clouds, ignored columns,
//   dropped normals)
// Throws InputError with one line "PATH:LINE: message" (ASCII data and headers) or
// "PATH: message" (binary data: "point N" names the point): unreadable file, unknown extension,
// malformed header, missing x/y/z, a field that is not a finite number, wrong field counts, fewer
// or more points than the header declares, payload shorter than the header declares, no points.
PointCloud read_point_cloud(const std::string& path, std::vector<std::string>* notes = nullptr);

// Same as read_point_cloud, from the file's content `text`; `path` names it in messages and its
// extension chooses the format.
PointCloud parse_point_cloud(std::string_view text, const std::string& path,
                             std::vector<std::string>* notes = nullptr);

// True when read_point_cloud reads files with the extension of `path`.
bool is_point_cloud_file(const std::string& path);

} // namespace interlin
