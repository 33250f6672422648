// The .rf model language: lexer and recursive-descent parser.
#include "model_parser.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/limits.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace interlin::rf::detail {

void throw_at(const std::string& file, Pos pos, const std::string& message) {
  throw InputError(file + ":" + std::to_string(pos.line) + ":" + std::to_string(pos.column) + ": " +
                   message);
}

namespace {

struct Token {
  enum class Kind { number, ident, symbol, text, end };
  Kind kind = Kind::end;
  Pos pos;
  std::string text; // identifier, number text or symbol (one of + - * / ^ ( ) , ; = [ ])
  double number = 0;
};

std::string describe(const Token& t) {
  switch (t.kind) {
  case Token::Kind::end:
    return "the end of the file";
  case Token::Kind::number:
    return "the number " + t.text;
  case Token::Kind::ident:
    return "'" + t.text + "'";
  case Token::Kind::text:
    return "the text \"" + t.text + "\"";
  default:
    return "'" + t.text + "'";
  }
}

bool is_ident_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// The number starting at s[i] (digits, an optional fraction unless the '.' begins MATLAB's
// '.*', './', '.^', an optional exponent); i moves past it. A number followed by a letter, an
// exponent without digits or a value out of a double's range is an error at `at`.
Token lex_number(const std::string& s, std::size_t& i, Pos at, const std::string& file) {
  const std::size_t b = i;
  while (i < s.size() && is_digit(s[i]))
    ++i;
  if (i < s.size() && s[i] == '.' &&
      !(i + 1 < s.size() && (s[i + 1] == '*' || s[i + 1] == '/' || s[i + 1] == '^')))
    for (++i; i < s.size() && is_digit(s[i]);)
      ++i;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-'))
      ++j;
    if (j >= s.size() || !is_digit(s[j]))
      throw_at(file, at,
               "malformed number '" + s.substr(b, j - b) + "': the exponent needs digits");
    for (i = j; i < s.size() && is_digit(s[i]);)
      ++i;
  }
  if (i < s.size() && is_ident_start(s[i]))
    throw_at(file, at,
             "malformed number '" + s.substr(b, i - b + 1) + "' (a number followed by a letter)");
  Token t;
  t.pos = at;
  t.kind = Token::Kind::number;
  t.text = s.substr(b, i - b);
  const std::string digits = t.text[0] == '.' ? "0" + t.text : t.text; // from_chars needs a digit
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), t.number);
  if (r.ec == std::errc::result_out_of_range || !std::isfinite(t.number))
    throw_at(file, at, "number " + t.text + " is out of the range of a double");
  return t;
}

std::vector<Token> lex(const std::string& s, const std::string& file) {
  std::vector<Token> out;
  std::size_t i = 0;
  int line = 1;
  std::size_t line_start = 0;
  if (s.compare(0, 3, "\xEF\xBB\xBF") == 0) { // UTF-8 byte-order mark
    i = 3;
    line_start = 3;
  }
  auto pos = [&](std::size_t at) { return Pos{line, static_cast<int>(at - line_start) + 1}; };
  while (i < s.size()) {
    const char c = s[i];
    if (c == '\n') {
      ++line;
      line_start = ++i;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++i;
      continue;
    }
    if (c == '%' || c == '#' || (c == '/' && i + 1 < s.size() && s[i + 1] == '/')) {
      while (i < s.size() && s[i] != '\n')
        ++i;
      continue;
    }
    Token t;
    t.pos = pos(i);
    if (is_digit(c) || (c == '.' && i + 1 < s.size() && is_digit(s[i + 1]))) {
      out.push_back(lex_number(s, i, t.pos, file));
      continue;
    }
    if (is_ident_start(c)) {
      const std::size_t b = i;
      while (i < s.size() && (is_ident_start(s[i]) || is_digit(s[i])))
        ++i;
      t.kind = Token::Kind::ident;
      t.text = s.substr(b, i - b);
      out.push_back(t);
      continue;
    }
    if (c == '.' && i + 1 < s.size() && (s[i + 1] == '*' || s[i + 1] == '/' || s[i + 1] == '^')) {
      t.kind = Token::Kind::symbol; // MATLAB's element-wise operators are the plain ones here
      t.text = std::string(1, s[i + 1]);
      i += 2;
      out.push_back(t);
      continue;
    }
    if (c == '"') { // a text: a file name, on one line, without escapes
      const std::size_t b = ++i;
      while (i < s.size() && s[i] != '"' && s[i] != '\n')
        ++i;
      if (i >= s.size() || s[i] != '"')
        throw_at(file, t.pos, "unterminated text: a closing '\"' is missing on this line");
      t.kind = Token::Kind::text;
      t.text = s.substr(b, i - b);
      ++i;
      out.push_back(t);
      continue;
    }
    static const std::string symbols = "+-*/^(),;=[]";
    if (symbols.find(c) != std::string::npos) {
      t.kind = Token::Kind::symbol;
      t.text = std::string(1, c);
      ++i;
      out.push_back(t);
      continue;
    }
    char buf[64];
    if (static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f)
      std::snprintf(buf, sizeof buf, "unexpected character '%c'", c);
    else
      std::snprintf(buf, sizeof buf,
                    "unexpected byte 0x%02X (only ASCII is allowed outside comments)",
                    static_cast<unsigned char>(c));
    throw_at(file, t.pos, buf);
  }
  Token end;
  end.kind = Token::Kind::end;
  end.pos = pos(i);
  out.push_back(end);
  return out;
}

class Parser {
public:
  Parser(std::vector<Token> tokens, const std::string& file) : t_(std::move(tokens)), file_(file) {}

  std::vector<Statement> program() {
    std::vector<Statement> out;
    while (peek().kind != Token::Kind::end)
      out.push_back(statement());
    return out;
  }

private:
  const Token& peek(int ahead = 0) const { return t_[std::min(i_ + ahead, t_.size() - 1)]; }
  bool is_symbol(const char* s, int ahead = 0) const {
    return peek(ahead).kind == Token::Kind::symbol && peek(ahead).text == s;
  }
  const Token& next() { return t_[std::min(i_++, t_.size() - 1)]; }
  [[noreturn]] void fail(const Token& at, const std::string& message) const {
    throw_at(file_, at.pos, message);
  }
  void expect(const char* symbol, const std::string& context) {
    if (!is_symbol(symbol))
      fail(peek(),
           std::string("expected '") + symbol + "' " + context + ", found " + describe(peek()));
    next();
  }
  std::string ident(const std::string& context) {
    if (peek().kind != Token::Kind::ident)
      fail(peek(), "expected a name " + context + ", found " + describe(peek()));
    return next().text;
  }

  Statement statement() {
    Statement st;
    const Token& first = peek();
    st.pos = first.pos;
    if (first.kind != Token::Kind::ident)
      fail(first, "expected a statement (NAME = expression;, param, def or box), found " +
                      describe(first));
    if (first.text == "def") {
      next();
      st.kind = Statement::Kind::def;
      st.name = ident("after 'def'");
      expect("(", "after the function name");
      if (!is_symbol(")"))
        for (;;) {
          st.param_pos.push_back(peek().pos);
          st.params.push_back(ident("(a parameter)"));
          if (is_symbol(")"))
            break;
          expect(",", "or ')' in the parameter list");
        }
      expect(")", "after the parameters");
      expect("=", "after the parameter list");
    } else if (first.text == "param") {
      next();
      st.kind = Statement::Kind::param;
      st.name = ident("after 'param'");
      expect("=", "after the parameter name");
    } else if (first.text == "box") {
      next();
      st.kind = Statement::Kind::box;
      expect("(", "after 'box' (box(x0, y0, z0, x1, y1, z1);)");
      for (int k = 0; k < 6; ++k) {
        st.exprs.push_back(expr(0));
        if (k < 5)
          expect(",", "between the six bounds of box(x0, y0, z0, x1, y1, z1)");
      }
      expect(")", "after the six bounds of box(x0, y0, z0, x1, y1, z1)");
      expect(";", "after the box statement");
      return st;
    } else {
      st.kind = Statement::Kind::assign;
      st.name = next().text;
      if (!is_symbol("="))
        fail(peek(), "expected '=' after '" + st.name +
                         "' (statements are NAME = expression;), found " + describe(peek()));
      next();
    }
    st.exprs.push_back(expr(0));
    if (!is_symbol(";"))
      fail(peek(), "expected ';' at the end of the statement, found " + describe(peek()));
    next();
    return st;
  }

  void check_depth(int depth) const {
    if (depth > limits::model_nesting)
      fail(peek(), "expression nested too deeply (more than " +
                       std::to_string(limits::model_nesting) + " levels; a fixed limit)");
  }

  // The node of the operator token `op` over its operand(s): unary with one, binary with two.
  // A chain such as a sum of many terms grows the tree's height without nesting: it is limited
  // like the expressions it becomes (the passes over both recurse along it).
  Ast apply(const Token& op, Ast a) const {
    Ast n;
    n.kind = Ast::Kind::unary;
    n.pos = op.pos;
    n.op = op.text[0];
    n.height = a.height + 1;
    n.args.push_back(std::move(a));
    if (n.height > limits::expression_depth)
      fail(op, "expression too long: more than " + std::to_string(limits::expression_depth) +
                   " chained operations (a fixed limit)");
    return n;
  }
  Ast apply(const Token& op, Ast a, Ast b) const {
    const int hb = b.height;
    Ast n = apply(op, std::move(a));
    n.kind = Ast::Kind::binary;
    n.height = std::max(n.height, hb + 1);
    n.args.push_back(std::move(b));
    return n;
  }

  // expr := term { (+|-) term }
  Ast expr(int depth) {
    check_depth(depth);
    Ast left = term(depth);
    while (is_symbol("+") || is_symbol("-")) {
      const Token& op = next();
      left = apply(op, std::move(left), term(depth));
    }
    return left;
  }
  // term := unary { (*|/) unary }
  Ast term(int depth) {
    Ast left = unary(depth);
    while (is_symbol("*") || is_symbol("/")) {
      const Token& op = next();
      left = apply(op, std::move(left), unary(depth));
    }
    return left;
  }
  // unary := (-|+) unary | power      (so -x^2 = -(x^2))
  Ast unary(int depth) {
    check_depth(depth);
    if (is_symbol("-") || is_symbol("+")) {
      const Token& op = next();
      return apply(op, unary(depth + 1));
    }
    return power(depth);
  }
  // power := primary [ ^ [-|+] primary ]; a^b^c is refused (MATLAB and mathematics disagree)
  Ast power(int depth) {
    Ast base = primary(depth);
    if (!is_symbol("^"))
      return base;
    const Token& op = next();
    Ast exponent;
    if (is_symbol("-") || is_symbol("+")) { // 2^-1
      const Token& sign = next();
      exponent = apply(sign, primary(depth + 1));
    } else {
      exponent = primary(depth + 1);
    }
    if (is_symbol("^"))
      fail(peek(), "a^b^c is ambiguous: write (a^b)^c or a^(b^c)");
    return apply(op, std::move(base), std::move(exponent));
  }
  Ast primary(int depth) {
    const Token& t = peek();
    Ast a;
    a.pos = t.pos;
    if (t.kind == Token::Kind::number) {
      next();
      a.kind = Ast::Kind::number;
      a.number = t.number;
      return a;
    }
    if (t.kind == Token::Kind::ident) {
      next();
      a.name = t.text;
      if (!is_symbol("(")) {
        a.kind = Ast::Kind::name;
        return a;
      }
      next();
      a.kind = Ast::Kind::call;
      a.args = list(")", "or ')' between the arguments of " + a.name + "(...)", depth);
      a.height = 1 + max_height(a.args);
      return a;
    }
    if (is_symbol("(")) {
      next();
      Ast inner = expr(depth + 1);
      expect(")",
             "to close '(' at " + std::to_string(t.pos.line) + ":" + std::to_string(t.pos.column));
      return inner;
    }
    if (t.kind == Token::Kind::text) {
      next();
      a.kind = Ast::Kind::text;
      a.name = t.text;
      return a;
    }
    if (is_symbol("[")) {
      next();
      a.kind = Ast::Kind::list;
      a.args = list("]", "or ']' in the list", depth);
      a.height = 1 + max_height(a.args);
      return a;
    }
    fail(t, "expected a number, a name, '(' or '[', found " + describe(t));
  }
  static int max_height(const std::vector<Ast>& items) {
    int h = 0;
    for (const Ast& item : items)
      h = std::max(h, item.height);
    return h;
  }
  // [ expr { , expr } ] close: the items of a call or a list, after its opening symbol.
  std::vector<Ast> list(const char* close, const std::string& between, int depth) {
    std::vector<Ast> items;
    if (!is_symbol(close))
      for (;;) {
        items.push_back(expr(depth + 1));
        if (is_symbol(close))
          break;
        expect(",", between);
      }
    next();
    return items;
  }

  std::vector<Token> t_;
  std::size_t i_ = 0;
  const std::string& file_;
};

} // namespace

std::vector<Statement> parse_model_text(const std::string& text, const std::string& file) {
  return Parser(lex(text, file), file).program();
}

} // namespace interlin::rf::detail
