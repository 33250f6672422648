// The bad-input table (issue 13): one row per case, over every subcommand. Each row runs one
// command line in a fresh directory that holds the row's input files, and states
//   - the exit status (0 accepted, 1 bad input or failed output, 2 wrong usage),
//   - for a failure, a pattern (ECMAScript regex, searched) for the single line on stderr,
//   - for an accepted input, the output files that must appear.
// For every row the directory afterwards holds exactly the inputs and those outputs (no partial
// output, no temporary file), and every input file is byte-for-byte unchanged.
// To add a case, add a row to cases() below; inputs are built by the helpers above it.
#include "support/test_support.h"

#include "interlin/interflatation/limits.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace fs = std::filesystem;
using interlin::test::TempDir;

namespace {

// ------------------------------------------------------------------------------- inputs --

// One file (or directory) of a case, created before the run.
struct Input {
  std::string path; // relative to the case directory
  std::string content;
  bool directory = false;
};

Input file(const std::string& path, std::string content) {
  return {path, std::move(content), false};
}
Input directory(const std::string& path) {
  return {path, "", true};
}

// `k` closed sections of `n` points each (ellipses growing along z), CSV with header.
std::string sections(int k = 3, long n = 8) {
  std::string s = "section,index,x,y,z\n";
  char row[128];
  for (int j = 0; j < k; ++j)
    for (long i = 0; i < n; ++i) {
      const double t = 2 * M_PI * double(i) / double(n), r = 1 + 0.1 * j;
      std::snprintf(row, sizeof row, "%d,%ld,%.17g,%.17g,%d\n", j, i, r * std::cos(t),
                    0.6 * r * std::sin(t), j);
      s += row;
    }
  return s;
}

// The same sections as plain "x y z" lines, blank lines between sections.
std::string plain_sections() {
  std::string s = "# x y z\n";
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 8; ++i)
      s += std::to_string(std::cos(M_PI * i / 4)) + " " + std::to_string(std::sin(M_PI * i / 4)) +
           " " + std::to_string(j) + "\n";
    s += "\n";
  }
  return s;
}

// Two guide lines through the sections' x extremes (index 0 and 4 of sections()).
std::string guides() {
  std::string s = "guide,index,x,y,z\n";
  for (int j = 0; j < 3; ++j)
    s += "LE," + std::to_string(j) + "," + std::to_string(1 + 0.1 * j) + ",0," + std::to_string(j) +
         "\n";
  for (int j = 0; j < 3; ++j)
    s += "TE," + std::to_string(j) + "," + std::to_string(-(1 + 0.1 * j)) + ",0," +
         std::to_string(j) + "\n";
  return s;
}

std::string points() {
  return "x,y,z\n0,0,0\n0.5,0.25,0\n2,0,0\n";
}

// A unit ball (F > 0 inside) with its box.
std::string ball() {
  return "% unit ball\nbox(-1.5, -1.5, -1.5, 1.5, 1.5, 1.5);\nres = sphere(x, y, z, 1);\n";
}

std::string profile_json() {
  return R"({"format": "interlin-cascade-profile", "version": 1,
 "parameters": {"relative_pitch": 0.75, "axial_width": 40, "stagger_deg": 40,
  "inlet_angle_deg": 90, "outlet_angle_deg": 13, "le_wedge_deg": 30, "te_wedge_deg": 6,
  "le_radius": 2.4, "te_radius": 0.4, "te_bend_deg": 13, "max_thickness_position": 0.35,
  "max_thickness": 0.15, "throat": 0}}
)";
}

std::string profile_toml() {
  return "format = \"interlin-cascade-profile\"\nversion = 1\n[parameters]\n"
         "relative_pitch = 0.75\naxial_width = 40.0\nstagger_deg = 40\ninlet_angle_deg = 90\n"
         "outlet_angle_deg = 13\nle_wedge_deg = 30\nte_wedge_deg = 6\nle_radius = 2.4\n"
         "te_radius = 0.4\nte_bend_deg = 13\nmax_thickness_position = 0.35\n"
         "max_thickness = 0.15\nthroat = 0\n";
}

// A model file: a unit box and `statements`.
std::string model(const std::string& statements) {
  return "box(0,0,0,1,1,1);\n" + statements + "\n";
}

// `n` user functions, each calling the previous one twice: 2^n expansions of f0.
std::string doubling_functions(int n) {
  std::string t = "def f0(t) = t * 1.5;\n";
  for (int i = 1; i <= n; ++i)
    t += "def f" + std::to_string(i) + "(t) = f" + std::to_string(i - 1) + "(t) + f" +
         std::to_string(i - 1) + "(t);\n";
  return t + "res = f" + std::to_string(n) + "(x);";
}

// profile_json() with a span law of `n` stations (radii 100, 101, ...).
std::string profile_span_json(int n) {
  std::string radii;
  for (int i = 0; i < n; ++i)
    radii += (i ? "," : "") + std::to_string(100 + i);
  const std::string j = profile_json();
  return j.substr(0, j.rfind('}')) + ", \"span\": {\"radius\": [" + radii + "]}}\n";
}

// `text` with a UTF-8 byte-order mark, with CRLF line ends.
std::string bom(const std::string& text) {
  return "\xEF\xBB\xBF" + text;
}
std::string crlf(const std::string& text) {
  std::string s;
  for (char c : text)
    s += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return s;
}

// `n` bytes of deterministic binary junk (all byte values, NUL included).
std::string junk(std::size_t n = 4096) {
  std::string s(n, '\0');
  unsigned x = 12345;
  for (char& c : s) {
    x = x * 1103515245u + 12345u;
    c = static_cast<char>(x >> 16);
  }
  return s;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A real implicit model file, written by `interlin implicit NAME -o m.ifl --resolution 8` from
// the file NAME holding `content` (sections(): kind section_body; ball(): kind normalized_rf).
std::string ifl_of(const std::string& name, const std::string& content) {
  const TempDir dir("table-ifl");
  std::ofstream(dir / name, std::ios::binary) << content;
  const std::string cmd = "cd '" + dir.path().string() + "' && " INTERLIN_CLI " implicit " + name +
                          " -o m.ifl --resolution 8 -q";
  if (std::system(cmd.c_str()) != 0)
    throw std::runtime_error("bad-input table: interlin implicit " + name + " failed");
  return slurp(dir.path() / "m.ifl");
}

// `text` with its first `from` (which must occur) replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos)
    throw std::logic_error("bad-input table: '" + from + "' not found");
  return text.replace(at, from.size(), to);
}

// `ifl` with its text field `name` set to `value`.
std::string with_text(const std::string& ifl, const std::string& name, const std::string& value) {
  const std::string head = "\ntext " + name + " ";
  const std::size_t at = ifl.find(head), from = at + head.size();
  if (at == std::string::npos)
    throw std::logic_error("bad-input table: text '" + name + "' not found");
  const std::size_t eol = ifl.find('\n', from), old = std::stoul(ifl.substr(from, eol - from));
  return ifl.substr(0, from) + std::to_string(value.size()) + "\n" + value +
         ifl.substr(eol + 1 + old);
}

// `ifl` with a NaN as the first value of the array whose header line is `header`.
std::string nan_in_array(std::string ifl, const std::string& header) {
  const std::size_t at = ifl.find(header);
  if (at == std::string::npos)
    throw std::logic_error("bad-input table: '" + header + "' not found");
  const double nan = std::nan("");
  std::memcpy(&ifl[at + header.size()], &nan, sizeof nan);
  return ifl;
}

// `text` repeated `n` times.
std::string repeat(const std::string& text, long n) {
  std::string s;
  s.reserve(text.size() * static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i)
    s += text;
  return s;
}

// `n` points on the unit sphere (a Fibonacci lattice), one "x y z" line each.
std::string sphere_cloud(int n = 200) {
  std::string s;
  char row[96];
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), a = 2.399963229728653 * i;
    std::snprintf(row, sizeof row, "%.17g %.17g %.17g\n", r * std::cos(a), r * std::sin(a), z);
    s += row;
  }
  return s;
}

// --------------------------------------------------------------------------------- cases --

struct Case {
  std::string name;                 // unique; printed when the row fails
  std::vector<Input> inputs;        // created in the case directory before the run
  std::string args;                 // after "interlin", run in the case directory
  int status;                       // expected exit status
  std::string error;                // status != 0: regex for the one line on stderr
  std::vector<std::string> outputs; // status 0: files the run must write
};

std::vector<Case> cases() {
  const Input s = file("s.csv", sections());
  const Input m = file("m.rf", ball());
  const Input p = file("p.csv", points());
  const Input pj = file("p.json", profile_json());
  const std::string body = ifl_of("s.csv", sections()); // kind section_body
  const Input b = file("b.ifl", body);
  const std::string normalised = ifl_of("m.rf", ball()); // kind normalized_rf
  const Input n = file("n.ifl", normalised);
  // A normalised model whose source calls ifl("l.ifl") (relative to l.rf, in the case's
  // directory), saved as l.ifl: loading it loads itself.
  const Input loop = file(
      "l.ifl",
      with_text(with_text(normalised, "source", "box(-1,-1,-1,1,1,1);\nres = ifl(\"l.ifl\");\n"),
                "path", "l.rf"));
  // One row per case, a row a line (or a few).
  // clang-format off
  return {
      // ---- interlin (no subcommand)
      {"no arguments", {}, "", 2, "^interlin: no command given", {}},
      {"unknown command", {}, "frobnicate", 2, "^interlin: unknown command 'frobnicate'", {}},
      // ---- loft: accepted encodings
      {"loft: UTF-8 BOM", {file("s.csv", bom(sections()))}, "loft s.csv -o o.json -q", 0, "",
       {"o.json"}},
      {"loft: CRLF", {file("s.csv", crlf(sections()))}, "loft s.csv -o o.json -q", 0, "",
       {"o.json"}},
      {"loft: BOM + CRLF plain x y z", {file("s.xyz", bom(crlf(plain_sections())))},
       "loft s.xyz -o o.stl -q", 0, "", {"o.stl"}},
      {"loft: guides with BOM + CRLF", {s, file("g.csv", bom(crlf(guides())))},
       "loft s.csv --guides g.csv -o o.igs -q", 0, "", {"o.igs"}},
      // ---- loft: unreadable and malformed inputs
      {"loft: binary junk", {file("s.csv", junk())}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv:1: ", {}},
      {"loft: empty file", {file("s.csv", "")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv: no data rows", {}},
      {"loft: comments only", {file("s.csv", "# nothing\n\n  \n")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv: no data rows", {}},
      {"loft: header only", {file("s.csv", "section,x,y,z\n")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv: no data rows after the header", {}},
      {"loft: a directory as input", {directory("s.csv")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv: cannot open: Is a directory", {}},
      {"loft: missing input", {}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv: cannot open: No such file", {}},
      {"loft: NaN", {file("s.csv", sections() + "3,0,nan,0,3\n")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv:26: column x: 'nan' is not a finite value", {}},
      {"loft: beyond the double range", {file("s.csv", sections() + "3,0,1e400,0,3\n")},
       "loft s.csv -o o.stl -q", 1, "^interlin: s\\.csv:26: column x: '1e400' is out of the range",
       {}},
      {"loft: truncated row", {file("s.csv", sections() + "3,0,1.5")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv:26: expected 5 comma-separated fields", {}},
      {"loft: NUL inside a number", {file("s.csv", sections() + std::string("3,0,1\0,0,3\n", 12))},
       "loft s.csv -o o.stl -q", 1, "^interlin: s\\.csv:26: column x: ", {}},
      {"loft: one section", {file("s.csv", sections(1))}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv: need at least 2 sections", {}},
      {"loft: three points", {file("s.csv", sections(2, 3))}, "loft s.csv -o o.stl -q", 1,
       "^interlin: s\\.csv:2: section 0 has 3 distinct point", {}},
      {"loft: guides binary junk", {s, file("g.csv", junk())},
       "loft s.csv --guides g.csv -o o.stl -q", 1, "^interlin: g\\.csv:1: ", {}},
      {"loft: guides empty", {s, file("g.csv", "")}, "loft s.csv --guides g.csv -o o.stl -q", 1,
       "^interlin: g\\.csv: no data rows", {}},
      {"loft: guides a directory", {s, directory("g")}, "loft s.csv --guides g -o o.stl -q", 1,
       "^interlin: g: cannot open: Is a directory", {}},
      {"loft: one section of 2000000 points (read in memory proportional to the file)",
       {file("s.csv", "section,x,y,z\n" + repeat("0,1.25,-0.5,2\n0,-0.5,1.25,2\n", 1000000))},
       "loft s.csv -o o.stl -q", 1, "^interlin: s\\.csv: need at least 2 sections", {}},
      // ---- loft: outputs
      {"loft: output is the input", {s}, "loft s.csv -o s.csv -q", 2,
       "^interlin loft: output 's\\.csv' is the input file 's\\.csv'", {}},
      {"loft: output is the input, other spelling", {s}, "loft s.csv -o ./s.csv -q", 2,
       "^interlin loft: output '\\./s\\.csv' is the input file 's\\.csv'", {}},
      {"loft: output is the guide file", {s, file("g.csv", guides())},
       "loft s.csv --guides g.csv -o g.csv -q", 2, "is the input file 'g\\.csv'", {}},
      {"loft: output given twice", {s}, "loft s.csv -o o.stl -o o.stl -q", 2,
       "^interlin loft: output 'o\\.stl' given twice", {}},
      {"loft: output directory missing", {s}, "loft s.csv -o o.stl -o no/o.igs -q", 1,
       "^interlin: cannot write no/o\\.igs: directory no does not exist", {}},
      {"loft: STEP output directory missing", {s}, "loft s.csv -o o.stl -o no/o.step --cap -q", 1,
       "^interlin: cannot write no/o\\.step: directory no does not exist", {}},
      {"loft: output is a directory", {s, directory("o.stl")}, "loft s.csv -o o.stl -q", 1,
       "^interlin: cannot write o\\.stl: it is a directory", {}},
      {"loft: output below a file", {s}, "loft s.csv -o s.csv/o.stl -q", 1,
       "^interlin: cannot write s\\.csv/o\\.stl: s\\.csv is not a directory", {}},
      {"loft: unwritable output directory", {s}, "loft s.csv -o /proc/interlin-o.stl -q", 1,
       "^interlin: cannot write /proc/interlin-o\\.stl: ", {}},
      {"loft: unknown output extension", {s}, "loft s.csv -o o.xyz -q", 2,
       "^interlin loft: output 'o\\.xyz': unknown extension", {}},
      // ---- loft: resources
      {"loft: --samples 1000000000,5", {s}, "loft s.csv -o o.stl --samples 1000000000,5 -q", 2,
       "^interlin loft: --samples 1000000000,5: .* triangles.* limit .*--max-triangles", {}},
      {"loft: --samples 100000,100000", {s}, "loft s.csv -o o.stl --samples 100000,100000 -q", 2,
       "--max-triangles", {}},
      // ---- eval
      {"eval: model BOM + CRLF", {file("m.rf", bom(crlf(ball()))), p},
       "eval m.rf p.csv -o o.csv -q", 0, "", {"o.csv"}},
      {"eval: points BOM + CRLF", {m, file("p.csv", bom(crlf(points())))},
       "eval m.rf p.csv -o o.csv -q", 0, "", {"o.csv"}},
      {"eval: model binary junk", {file("m.rf", junk()), p}, "eval m.rf p.csv -q", 1,
       "^interlin: m\\.rf:1:1: unexpected byte 0x", {}},
      {"eval: model empty", {file("m.rf", ""), p}, "eval m.rf p.csv -q", 1,
       "^interlin: m\\.rf: the model has no box statement", {}},
      {"eval: model a directory", {directory("m.rf"), p}, "eval m.rf p.csv -q", 1,
       "^interlin: m\\.rf: cannot open: Is a directory", {}},
      {"eval: points binary junk", {m, file("p.csv", junk())}, "eval m.rf p.csv -q", 1,
       "^interlin: p\\.csv:1: ", {}},
      {"eval: points empty", {m, file("p.csv", "")}, "eval m.rf p.csv -q", 1,
       "^interlin: p\\.csv: no header", {}},
      {"eval: points a directory", {m, directory("p.csv")}, "eval m.rf p.csv -q", 1,
       "^interlin: p\\.csv: cannot open: Is a directory", {}},
      {"eval: output is the points file", {m, p}, "eval m.rf p.csv -o p.csv -q", 2,
       "^interlin eval: output 'p\\.csv' is the input file 'p\\.csv'", {}},
      {"eval: output directory missing", {m, p}, "eval m.rf p.csv -o no/o.csv -q", 1,
       "^interlin: cannot write no/o\\.csv: directory no does not exist", {}},
      {"eval: parentheses nested 100000 deep",
       {file("m.rf", model("res = " + repeat("(", 100000) + "x" + repeat(")", 100000) + ";")), p},
       "eval m.rf p.csv -q", 1, "^interlin: m\\.rf:2:\\d+: expression nested too deeply", {}},
      {"eval: a sum of 1000000 terms",
       {file("m.rf", model("res = x" + repeat(" + x", 1000000) + ";")), p},
       "eval m.rf p.csv -q", 1, "^interlin: m\\.rf:2:\\d+: .*20000", {}},
      {"eval: a sum of 19990 terms, within the depth limit, differentiated",
       {file("m.rf", model("res = x" + repeat(" + x", 19990) + ";\n"
                           "res = normalize(res) * dx(res);")), p},
       "eval m.rf p.csv --gradient -o o.csv -q", 0, "", {"o.csv"}},
      {"eval: a Bezier region of 200 control points sampled 100000 times",
       {file("m.rf", model("res = bezier_region(x, y, 100000, [" + repeat("0, 0, 1, 0, ", 199) +
                           "1, 1]);")), p},
       "eval m.rf p.csv -q", 1, "^interlin: m\\.rf:2:1: .*model-size limit.*--max-model-size", {}},
      {"eval: function calls doubling 60 times",
       {file("m.rf", model(doubling_functions(60))), p},
       "eval m.rf p.csv -q", 1, "^interlin: m\\.rf:\\d+:\\d+: .*limit.*--max-model-size", {}},
      // ---- mesh
      {"mesh: model BOM + CRLF", {file("m.rf", bom(crlf(ball())))},
       "mesh m.rf -o o.stl --resolution 8 -q", 0, "", {"o.stl"}},
      {"mesh: model binary junk", {file("m.rf", junk())}, "mesh m.rf -o o.stl -q", 1,
       "^interlin: m\\.rf:1:1: unexpected byte 0x", {}},
      {"mesh: model empty", {file("m.rf", "")}, "mesh m.rf -o o.stl -q", 1,
       "^interlin: m\\.rf: the model has no box statement", {}},
      {"mesh: output is the model", {file("m.stl", ball())}, "mesh m.stl -o m.stl -q", 2,
       "^interlin mesh: output 'm\\.stl' is the input file 'm\\.stl'", {}},
      {"mesh: --resolution 100000", {m}, "mesh m.rf -o o.stl --resolution 100000 -q", 2,
       "^interlin mesh: --resolution 100000: asks for a grid of .* nodes, more than the limit of "
       "1100000000 \\(raise it with --max-grid-nodes N\\)", {}},
      {"mesh: --cell 1e-9", {m}, "mesh m.rf -o o.stl --cell 1e-9 -q", 2, "--max-grid-nodes", {}},
      {"mesh: --volume tet, model BOM + CRLF", {file("m.rf", bom(crlf(ball())))},
       "mesh m.rf -o o.msh -o o.vtu --volume tet --resolution 8 -q", 0, "", {"o.msh", "o.vtu"}},
      {"mesh: --volume tet --resolution 1000", {m},
       "mesh m.rf -o o.msh --volume tet --resolution 1000 -q", 2,
       "^interlin mesh: --resolution 1000: asks for up to .* volume elements, more than the limit "
       "of \\d+ \\(raise it with --max-elements N\\)", {}},
      {"mesh: --volume hex --cell 0.005", {m}, "mesh m.rf -o o.inp --volume hex --cell 0.005 -q", 2,
       "--max-elements", {}},
      {"mesh: --max-elements without --volume", {m},
       "mesh m.rf -o o.stl --max-elements 10 -q", 2,
       "^interlin mesh: --max-elements needs --volume", {}},
      {"mesh: --volume with an unknown kind", {m}, "mesh m.rf -o o.msh --volume prism -q", 2,
       "^interlin mesh: --volume expects one of", {}},
      {"mesh: --boundary cut with --margin", {m},
       "mesh m.rf -o o.msh --volume tet --margin 0.2 -q", 2,
       "^interlin mesh: --margin applies to the projected layer", {}},
      {"mesh: --boundary cut with --volume hex", {m},
       "mesh m.rf -o o.msh --volume hex --boundary cut -q", 2,
       "^interlin mesh: --boundary expects one of", {}},
      {"mesh: --boundary dual with --volume tet", {m},
       "mesh m.rf -o o.msh --volume tet --boundary dual -q", 2,
       "^interlin mesh: --boundary expects one of", {}},
      {"mesh: --boundary pillow with --volume tet", {m},
       "mesh m.rf -o o.msh --volume tet --boundary pillow -q", 2,
       "^interlin mesh: --boundary expects one of", {}},
      {"mesh: --boundary pillow with --margin", {m},
       "mesh m.rf -o o.msh --volume hex --boundary pillow --margin 0.2 -q", 2,
       "^interlin mesh: --margin applies to the projected layer", {}},
      {"mesh: --boundary dual with --margin", {m},
       "mesh m.rf -o o.msh --volume hex --boundary dual --margin 0.2 -q", 2,
       "^interlin mesh: --margin applies to the projected layer", {}},
      {"mesh: --volume output with an unknown extension", {m},
       "mesh m.rf -o o.csv --volume tet -q", 2, "unknown extension for --volume", {}},
      {"mesh: no body in the box",
       {file("m.rf", "box(-1,-1,-1,1,1,1);\nres = sphere(x - 5, y, z, 1);\n")},
       "mesh m.rf -o o.stl --resolution 8 -q", 1, "^interlin: m\\.rf: no surface in the box", {}},
      // ---- implicit models (.ifl): eval and mesh read them like .rf models
      {"eval: section body .ifl", {b, p}, "eval b.ifl p.csv -o o.csv --gradient -q", 0, "",
       {"o.csv"}},
      {"mesh: normalised model .ifl", {n}, "mesh n.ifl -o o.stl --resolution 8 -q", 0, "",
       {"o.stl"}},
      {"mesh: section body .ifl --volume hex", {b},
       "mesh b.ifl -o o.vtu --volume hex --resolution 8 -q", 0, "", {"o.vtu"}},
      {"eval: .ifl truncated", {file("b.ifl", body.substr(0, body.size() / 2)), p},
       "eval b.ifl p.csv -q", 1, "^interlin: b\\.ifl:\\d+: .*the file ends before", {}},
      {"eval: .ifl empty", {file("b.ifl", ""), p}, "eval b.ifl p.csv -q", 1,
       "^interlin: b\\.ifl:1: unexpected end of file", {}},
      {"eval: .ifl binary junk", {file("b.ifl", junk()), p}, "eval b.ifl p.csv -q", 1,
       "^interlin: b\\.ifl:1: not an interlin implicit model file", {}},
      {"eval: .ifl a directory", {directory("b.ifl"), p}, "eval b.ifl p.csv -q", 1,
       "^interlin: b\\.ifl: cannot open: Is a directory", {}},
      {"eval: .ifl of a newer version",
       {file("b.ifl", replaced(body, "interlin-ifl 1\n", "interlin-ifl 2\n")), p},
       "eval b.ifl p.csv -q", 1, "^interlin: b\\.ifl:1: container version 2 is newer", {}},
      {"eval: .ifl of an unknown model kind",
       {file("b.ifl", replaced(body, "block section_body", "block section_bodz")), p},
       "eval b.ifl p.csv -q", 1, "^interlin: b\\.ifl:2: .*unknown model kind", {}},
      {"eval: .ifl with a field of the wrong shape",
       {file("b.ifl", replaced(body, "array edge_u f64 2 2\n", "array edge_u f64 4\n")), p},
       "eval b.ifl p.csv -q", 1, "^interlin: b\\.ifl:2: .*array 'edge_u' must be 2 x 2, got 4", {}},
      {"eval: .ifl with NaN in an array", {file("b.ifl", nan_in_array(body, "array box f64 6\n")), p},
       "eval b.ifl p.csv -q", 1, "^interlin: b\\.ifl:\\d+: array box: value 0 is not finite", {}},
      {"eval: .ifl with a NaN number",
       {file("b.ifl", replaced(body, "number band_inner ", "number band_inner nan\nnumber x ")), p},
       "eval b.ifl p.csv -q", 1, "^interlin: b\\.ifl:\\d+: number band_inner: 'nan' is not finite", {}},
      {"eval: .ifl with --set", {b, p}, "eval b.ifl p.csv --set r=1 -q", 2,
       "^interlin eval: --set and --var apply to R-function models \\(\\.rf\\) only", {}},
      {"eval: .ifl whose model loads itself", {loop, p}, "eval l.ifl p.csv -q", 1,
       "^interlin: .*l\\.ifl is being loaded already: ifl\\(\"\\.\\.\\.\"\\) calls in a cycle", {}},
      {"eval: .rf calling ifl() of a model that loads itself",
       {file("m.rf", model("res = ifl(\"l.ifl\");")), loop, p}, "eval m.rf p.csv -q", 1,
       "^interlin: m\\.rf:2:\\d+: .*calls in a cycle", {}},
      {"eval: .rf calling ifl() of a missing file", {file("m.rf", model("res = ifl(\"no.ifl\");")), p},
       "eval m.rf p.csv -q", 1, "^interlin: m\\.rf:2:\\d+: .*no\\.ifl: cannot open: No such file", {}},
      {"mesh: .ifl truncated", {file("b.ifl", body.substr(0, body.size() / 2))},
       "mesh b.ifl -o o.stl -q", 1, "^interlin: b\\.ifl:\\d+: ", {}},
      {"mesh: output is the .ifl", {b}, "mesh b.ifl -o b.ifl -q", 2,
       "^interlin mesh: output 'b\\.ifl': unknown extension", {}},
      // ---- implicit
      {"implicit: sections BOM + CRLF", {file("s.csv", bom(crlf(sections())))},
       "implicit s.csv -o o.ifl --resolution 8 -q", 0, "", {"o.ifl"}},
      {"implicit: model BOM + CRLF", {file("m.rf", bom(crlf(ball())))},
       "implicit m.rf -o o.ifl --resolution 8 -q", 0, "", {"o.ifl"}},
      {"implicit: sections empty", {file("s.csv", "")}, "implicit s.csv -o o.ifl -q", 1,
       "^interlin: s\\.csv: no data rows", {}},
      {"implicit: sections binary junk", {file("s.csv", junk())}, "implicit s.csv -o o.ifl -q", 1,
       "^interlin: s\\.csv:1: ", {}},
      {"implicit: ragged rows", {file("s.csv", sections() + "3,0,1.5,0\n3,1,1,1,3,9\n")},
       "implicit s.csv -o o.ifl -q", 1, "^interlin: s\\.csv:26: expected 5 comma-separated fields",
       {}},
      {"implicit: an .ifl given as sections", {b}, "implicit b.ifl -o o.ifl -q", 2,
       "^interlin implicit: input 'b\\.ifl': unknown kind", {}},
      {"loft: an .ifl given as sections", {b}, "loft b.ifl -o o.stl -q", 1,
       "^interlin: b\\.ifl:1: no header", {}},
      {"implicit: output is the input", {s}, "implicit s.csv -o s.csv -q", 2,
       "^interlin implicit: output 's\\.csv': the model file must end in \\.ifl", {}},
      {"implicit: --resolution 1024", {s}, "implicit s.csv -o o.ifl --resolution 1024 -q", 2,
       "^interlin implicit: --resolution 1024: asks for a grid of up to .* nodes, more than the "
       "limit of 4000000 \\(raise it with --max-grid-nodes N\\)", {}},
      {"implicit: --resolution 200 of a model", {m}, "implicit m.rf -o o.ifl --resolution 200 -q", 2,
       "--max-grid-nodes", {}},
      {"implicit: model binary junk", {file("m.rf", junk())}, "implicit m.rf -o o.ifl -q", 1,
       "^interlin: m\\.rf:1:1: unexpected byte 0x", {}},
      // ---- profile
      {"profile: JSON with BOM + CRLF", {file("p.json", bom(crlf(profile_json())))},
       "profile p.json -o o.csv -q", 0, "", {"o.csv"}},
      {"profile: TOML with BOM + CRLF", {file("p.toml", bom(crlf(profile_toml())))},
       "profile p.toml -o o.csv -q", 0, "", {"o.csv"}},
      {"profile: JSON binary junk", {file("p.json", junk())}, "profile p.json -o o.csv -q", 1,
       "^interlin: p\\.json:\\d+: JSON syntax error", {}},
      {"profile: TOML binary junk", {file("p.toml", junk())}, "profile p.toml -o o.csv -q", 1,
       "^interlin: p\\.toml:\\d+: TOML syntax error", {}},
      {"profile: JSON empty", {file("p.json", "")}, "profile p.json -o o.csv -q", 1,
       "^interlin: p\\.json:1: JSON syntax error", {}},
      {"profile: a directory", {directory("p.json")}, "profile p.json -o o.csv -q", 1,
       "^interlin: p\\.json: cannot open: Is a directory", {}},
      {"profile: output and curvature the same file", {pj},
       "profile p.json -o o.csv --curvature o.csv -q", 2,
       "^interlin profile: output 'o\\.csv' given twice", {}},
      {"profile: --points 100000,100000 on a span of 60",
       {file("p.json", profile_span_json(60))},
      "profile p.json -o o.csv --points 100000,100000 -q",
      1,
      "^interlin: p\\.json: .* points.* limit .*--max-points",
      {}},
      // ---- implicit SCAN (point clouds)
      {"implicit: cloud accepted", {file("c.xyz", sphere_cloud())}, "implicit c.xyz -o o.ifl -q",
       0, "", {"o.ifl"}},
      {"implicit: cloud binary junk .pcd", {file("c.pcd", junk())}, "implicit c.pcd -o o.ifl -q",
       1, "^interlin: c\\.pcd:1: not a PCD file", {}},
      {"implicit: cloud binary junk .ply", {file("c.ply", junk())}, "implicit c.ply -o o.ifl -q",
       1, "^interlin: c\\.ply:1: not a PLY file", {}},
      {"implicit: cloud empty", {file("c.xyz", "")}, "implicit c.xyz -o o.ifl -q", 1,
       "^interlin: c\\.xyz: .*(empty|no points)", {}},
      {"implicit: cloud of 3 points", {file("c.xyz", "0 0 0\n1 0 0\n0 1 0\n")},
       "implicit c.xyz -o o.ifl -q", 1, "^interlin: c\\.xyz: only 3 distinct point", {}},
      {"implicit: cloud with NaN", {file("c.xyz", sphere_cloud(30) + "0 nan 1\n")},
       "implicit c.xyz -o o.ifl -q", 1, "^interlin: c\\.xyz:31: column y: 'nan' is not a finite", {}},
      {"implicit: cloud ragged", {file("c.xyz", sphere_cloud(30) + "0 1\n")},
       "implicit c.xyz -o o.ifl -q", 1, "^interlin: c\\.xyz:31: expected 3 fields", {}},
      {"implicit: cloud of one repeated point", {file("c.xyz", repeat("1 2 3\n", 50))},
       "implicit c.xyz -o o.ifl -q", 1, "^interlin: c\\.xyz: only 1 distinct point", {}},
      {"implicit: cloud on a plane", {file("c.xyz", repeat("0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 3 0\n", 1) +
                                              "3 1 0\n4 4 0\n5 2 0\n2 5 0\n6 1 0\n7 3 0\n"
                                              "1 7 0\n8 8 0\n3 9 0\n9 2 0\n4 6 0\n6 6 0\n"
                                              "7 7 0\n2 8 0\n9 9 0\n5 5 0\n")},
       "implicit c.xyz -o o.ifl -q", 1, "^interlin: c\\.xyz: all 21 points lie on one plane", {}},
      {"implicit: .csv without a header", {file("c.csv", "0,0,0\n1,0,0\n0,1,0\n")},
       "implicit c.csv -o o.ifl -q", 1, "^interlin: c\\.csv:1: a \\.csv file without a header", {}},
      {"implicit: cloud a directory", {directory("c.xyz")}, "implicit c.xyz -o o.ifl -q", 1,
       "^interlin: c\\.xyz: cannot open: Is a directory", {}},
      {"implicit: no radial slices", {file("c.xyz", sphere_cloud())},
       "implicit c.xyz -o o.ifl --slices radial -q", 1, "^interlin: c\\.xyz: no radial slices found",
       {}},
      {"implicit: --slices none with --margin", {file("c.xyz", sphere_cloud())},
       "implicit c.xyz -o o.ifl --slices none --margin 0.1 -q", 2,
       "^interlin implicit: --margin applies to sections and sectioned scans", {}},
      {"implicit: --noise nan", {file("c.xyz", sphere_cloud())},
       "implicit c.xyz -o o.ifl --noise nan -q", 2, "^interlin implicit: --noise", {}},
  };
  // clang-format on
}

// ----------------------------------------------------------------------------- running --

// Every entry below `dir` (relative paths), directories included.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> out;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    out.insert(fs::relative(e.path(), dir).string());
  return out;
}

struct Outcome {
  int status;
  std::string err;
};

// Runs `interlin ARGS` in `dir`, stdout and stderr captured outside it. Outside the sanitizer
// build the run gets 4 GB of address space and 5 minutes: a case that claims more fails here
// instead of taking the machine down.
Outcome run_in(const fs::path& dir, const std::string& args) {
  const TempDir io("table-io");
  const std::string err = io / "stderr.txt";
#ifdef INTERLIN_SANITIZED
  const std::string cap = "";
#else
  const std::string cap = "ulimit -v 4000000; ";
#endif
  const std::string cmd = "cd '" + dir.string() + "' && " + cap + "timeout 300 " INTERLIN_CLI " " +
                          args + " >" + (io / "stdout.txt") + " 2>" + err;
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(err)};
}

void check_case(const Case& c) {
  INFO("case: " << c.name << "\ncommand: interlin " << c.args);
  const TempDir dir("table");
  std::set<std::string> expected;
  for (const Input& in : c.inputs) {
    const fs::path path = dir.path() / in.path;
    if (in.directory) {
      fs::create_directories(path);
    } else {
      std::ofstream(path, std::ios::binary) << in.content;
    }
    expected.insert(in.path);
  }
  const Outcome r = run_in(dir.path(), c.args);
  INFO("stderr: " << r.err);
  CHECK(r.status == c.status);
  if (c.status != 0) {
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(std::regex_search(r.err, std::regex(c.error)));
  }
  for (const std::string& o : c.outputs) {
    CHECK(fs::is_regular_file(dir.path() / o));
    expected.insert(o);
  }
  CHECK(listing(dir.path()) == expected); // no partial output, no temporary
  for (const Input& in : c.inputs)
    if (!in.directory)
      CHECK(slurp(dir.path() / in.path) == in.content);
}

} // namespace

TEST_CASE("bad-input table: every row's status, message, outputs and untouched inputs",
          "[cli][table]") {
  const std::vector<Case> all = cases();
  std::set<std::string> names;
  for (const Case& c : all)
    CHECK(names.insert(c.name).second); // names identify the rows
  CHECK(all.size() >= 40);
  for (const Case& c : all)
    check_case(c);
}

TEST_CASE("limits: every help text states the defaults of limits.h", "[cli][table]") {
  const auto help = [&](const std::string& command) {
    const TempDir io("table-io");
    std::system((INTERLIN_CLI " " + command + " --help >" + (io / "out.txt")).c_str());
    return slurp(io / "out.txt");
  };
  using namespace interlin::limits;
  CHECK_THAT(help("loft"), Catch::Contains("(default " + std::to_string(mesh_triangles)));
  const std::string mesh = help("mesh");
  CHECK_THAT(mesh, Catch::Contains("(default " + std::to_string(mesh_triangles)) &&
                       Catch::Contains("(default " + std::to_string(grid_nodes)) &&
                       Catch::Contains("(default " + std::to_string(model_size)) &&
                       Catch::Contains("(default " + std::to_string(volume_tetrahedra)) &&
                       Catch::Contains(std::to_string(volume_hexahedra) + " hexahedra"));
  CHECK_THAT(help("eval"), Catch::Contains("(default " + std::to_string(model_size)));
  CHECK_THAT(help("profile"), Catch::Contains("(default " + std::to_string(profile_points)));
  CHECK_THAT(help("implicit"), Catch::Contains("(default " + std::to_string(implicit_grid_nodes)));
}
