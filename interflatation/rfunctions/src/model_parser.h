#pragma once
// Internal: the .rf model language's syntax tree and parser (docs/formats.md, "R-function model
// files"). Errors are InputError("FILE:LINE:COLUMN: message").

#include <memory>
#include <string>
#include <vector>

namespace interlin::rf::detail {

struct Pos {
  int line = 1, column = 1;
};

struct Ast {
  enum class Kind { number, name, call, unary, binary, list, text };
  Kind kind = Kind::number;
  Pos pos;
  double number = 0;
  std::string name; // variable or function name; the characters of a text ("...")
  char op = 0;      // + - * / ^ for unary and binary
  int height = 1;   // nodes on the longest path down to a leaf (the recursion depth of passes)
  std::vector<Ast> args;
};

struct Statement {
  enum class Kind { assign, param, def, box };
  Kind kind = Kind::assign;
  Pos pos;                         // of the statement's first token
  std::string name;                // assigned variable, parameter or function
  std::vector<std::string> params; // def parameters
  std::vector<Pos> param_pos;
  std::vector<Ast> exprs; // the value (one), or the six box bounds
};

// Parses a whole model text. `file` names the source in error messages.
std::vector<Statement> parse_model_text(const std::string& text, const std::string& file);

// "FILE:LINE:COLUMN: message"
[[noreturn]] void throw_at(const std::string& file, Pos pos, const std::string& message);

} // namespace interlin::rf::detail
