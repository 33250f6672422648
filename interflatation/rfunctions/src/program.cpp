// Compiling an expression into a register program and evaluating it in blocks: one loop over
// the block per instruction (values), or per instruction on dual numbers (value + gradient).
#include "interlin/interflatation/rfunctions/expression.h"

#include "node.h"
#include "op_kernels.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace interlin::rf {

using detail::Node;
using detail::NodePtr;
using detail::Op;
using detail::Polyline;

namespace {

constexpr int kBlock = 256; // points per block: the registers of a block stay in L1/L2

struct Instr {
  Op op;
  int dst = 0, a = 0, b = 0; // register slots; b = a for unary operations
  double k = 0;
  const Polyline* curve = nullptr;
  int c = 0; // third operand slot (field operations), else a
  const ImplicitFunction* field = nullptr;
};

struct Program {
  std::vector<Instr> code;
  int slots = 0;
  int out = 0;
  std::vector<std::shared_ptr<const Polyline>> curves;         // keeps the curve tables alive
  std::vector<std::shared_ptr<const ImplicitFunction>> fields; // and the fields
};

// Merges equal sub-expressions (same operation, constant and operands) into one numbered node,
// children before parents.
class Linearizer {
public:
  struct Item {
    Op op;
    double k;
    int a, b;
    std::shared_ptr<const Polyline> curve;
    int c;
    std::shared_ptr<const ImplicitFunction> field;
  };
  std::vector<Item> items;

  int visit(const NodePtr& n) {
    auto seen = by_ptr_.find(n.get());
    if (seen != by_ptr_.end())
      return seen->second;
    const int a = n->a ? visit(n->a) : -1;
    const int b = n->b ? visit(n->b) : -1;
    const int c = n->c ? visit(n->c) : -1;
    std::uint64_t kbits;
    std::memcpy(&kbits, &n->k, sizeof kbits);
    const Key key{static_cast<int>(n->op), kbits, a, b, n->curve.get(), c, n->field.get()};
    auto [it, inserted] = by_key_.emplace(key, static_cast<int>(items.size()));
    if (inserted)
      items.push_back({n->op, n->k, a, b, n->curve, c, n->field});
    by_ptr_.emplace(n.get(), it->second);
    return it->second;
  }

private:
  using Key =
      std::tuple<int, std::uint64_t, int, int, const Polyline*, int, const ImplicitFunction*>;
  std::map<Key, int> by_key_;
  std::unordered_map<const Node*, int> by_ptr_;
};

using Items = std::vector<Linearizer::Item>;

// Item i's instruction, operands still item ids; a constant operand of + - * / becomes the
// instruction's k (immediate form), x^2 becomes a square.
Instr immediate_form(const Items& items, int i) {
  const auto& it = items[i];
  auto is_c = [&](int id) { return id >= 0 && items[id].op == Op::constant; };
  const bool ca = is_c(it.a), cb = is_c(it.b);
  if (it.op == Op::add && (ca || cb))
    return {Op::add_k, i, ca ? it.b : it.a, ca ? it.b : it.a, items[ca ? it.a : it.b].k};
  if (it.op == Op::sub && cb)
    return {Op::add_k, i, it.a, it.a, -items[it.b].k};
  if (it.op == Op::sub && ca)
    return {Op::k_sub, i, it.b, it.b, items[it.a].k};
  if (it.op == Op::mul && (ca || cb))
    return {Op::mul_k, i, ca ? it.b : it.a, ca ? it.b : it.a, items[ca ? it.a : it.b].k};
  if (it.op == Op::div && cb)
    return {Op::div_k, i, it.a, it.a, items[it.b].k};
  if (it.op == Op::div && ca)
    return {Op::k_div, i, it.b, it.b, items[it.a].k};
  if (it.op == Op::pow_k && it.k == 2)
    return {Op::square, i, it.a, it.a, 0};
  return {
      it.op,         i, it.a, it.b < 0 ? it.a : it.b, it.k, it.curve.get(), it.c < 0 ? it.a : it.c,
      it.field.get()};
}

// The instructions the root needs, children before parents (constants folded into immediates
// are not materialised).
std::vector<Instr> select_instructions(const Items& items, int root_id) {
  const int n = static_cast<int>(items.size());
  std::vector<bool> needed(n, false);
  std::vector<Instr> pending(n);
  needed[root_id] = true;
  for (int i = n - 1; i >= 0; --i) {
    if (!needed[i])
      continue;
    pending[i] = immediate_form(items, i);
    if (detail::arity(items[i].op) > 0) {
      needed[pending[i].a] = true;
      needed[pending[i].b] = true;
      needed[pending[i].c] = true;
    }
  }
  std::vector<Instr> code;
  for (int i = 0; i < n; ++i)
    if (needed[i])
      code.push_back(pending[i]);
  return code;
}

// Register allocation: a slot is freed after the last instruction that reads it; the
// destination is taken before the operands are freed, so no instruction writes its input.
// Rewrites `code`'s item ids into slots; returns the number of slots and the root's slot.
std::pair<int, int> allocate_registers(const Items& items, int root_id, std::vector<Instr>& code) {
  const int n = static_cast<int>(items.size());
  std::vector<int> last_use(n, -1);
  for (int j = 0; j < static_cast<int>(code.size()); ++j)
    if (detail::arity(items[code[j].dst].op) > 0) {
      last_use[code[j].a] = j;
      last_use[code[j].b] = j;
      last_use[code[j].c] = j;
    }
  last_use[root_id] = static_cast<int>(code.size());
  std::vector<int> slot_of(n, -1), free_slots;
  int slots = 0;
  for (int j = 0; j < static_cast<int>(code.size()); ++j) {
    Instr& in = code[j];
    const int item = in.dst, ia = in.a, ib = in.b, ic = in.c; // item ids, before slots
    const bool leaf = detail::arity(items[item].op) == 0;
    if (!leaf) {
      in.a = slot_of[in.a];
      in.b = slot_of[in.b];
      in.c = slot_of[in.c];
    } else {
      in.a = in.b = in.c = 0;
    }
    int s;
    if (!free_slots.empty()) {
      s = free_slots.back();
      free_slots.pop_back();
    } else {
      s = slots++;
    }
    slot_of[item] = s;
    in.dst = s;
    if (!leaf)
      for (int operand : {ia, ib, ic})
        if (last_use[operand] == j && slot_of[operand] >= 0) {
          free_slots.push_back(slot_of[operand]);
          slot_of[operand] = -1; // freed once, even when read twice
        }
  }
  return {slots, slot_of[root_id]};
}

Program build_program(const NodePtr& root) {
  Linearizer lin;
  const int root_id = lin.visit(root);
  Program p;
  p.code = select_instructions(lin.items, root_id);
  std::tie(p.slots, p.out) = allocate_registers(lin.items, root_id, p.code);
  for (const auto& it : lin.items) {
    if (it.curve)
      p.curves.push_back(it.curve);
    if (it.field)
      p.fields.push_back(it.field);
  }
  return p;
}

// The value handed out: NaN (undefined) is outside, infinities become the largest finite values.
double finite_value(double v) {
  constexpr double big = std::numeric_limits<double>::max();
  return v != v ? -big : std::clamp(v, -big, big);
}

// ---- value kernel --------------------------------------------------------------------------

// N > 0: a full block of N points (a constant trip count); N = 0: n points.
template <Op O, int N>
void run_values(double* __restrict r, const double* __restrict A, const double* __restrict B, int n,
                double k) {
  const int len = N > 0 ? N : n;
  for (int i = 0; i < len; ++i)
    r[i] = detail::value<O>(A[i], B[i], k);
  if constexpr (O == Op::and0 || O == Op::or0) {
    for (int i = 0; i < len; ++i)
      if (!detail::is_finite(r[i]))
        r[i] = detail::r0_nonfinite(A[i], B[i], O == Op::and0 ? -1.0 : 1.0);
  }
}

void run_curve(const Instr& in, double* r, const double* A, const double* B, int n) {
  for (int i = 0; i < n; ++i) {
    double du = 0, dv = 0;
    const double d = in.curve->signed_distance(A[i], B[i], &du, &dv);
    r[i] = in.op == Op::curve ? d : in.op == Op::curve_du ? du : dv;
  }
}

// The field operations on a block: the body's function at the points (A, B, C), with its
// gradient unless only the value is asked for. The body may itself be a compiled program (it
// runs on its own scratch level).
void field_block(const Instr& in, const double* A, const double* B, const double* C, int n,
                 bool with_gradient, Eigen::VectorXd& F, Points3& G) {
  Points3 P(n, 3);
  for (int i = 0; i < n; ++i)
    P.row(i) << A[i], B[i], C[i];
  F.resize(n);
  G.resize(n, 3);
  if (with_gradient)
    in.field->gradient(P, F, G);
  else
    in.field->value(P, F);
}

void run_field(const Instr& in, double* r, const double* A, const double* B, const double* C,
               int n) {
  Eigen::VectorXd F;
  Points3 G;
  field_block(in, A, B, C, n, in.op != Op::field, F, G);
  const int axis = static_cast<int>(in.op) - static_cast<int>(Op::field_dx);
  for (int i = 0; i < n; ++i)
    r[i] = in.op == Op::field ? F(i) : G(i, axis);
}

template <int N>
void evaluate_block(const Program& p, const double* const xyz[3], int n, double* regs,
                    double* out) {
  const double *X = xyz[0], *Y = xyz[1], *Z = xyz[2];
  auto reg = [&](int s) { return regs + static_cast<std::ptrdiff_t>(s) * kBlock; };
  for (const Instr& in : p.code) {
    double* r = reg(in.dst);
    const double* A = reg(in.a);
    const double* B = reg(in.b);
    switch (in.op) {
    case Op::field:
    case Op::field_dx:
    case Op::field_dy:
    case Op::field_dz:
      run_field(in, r, A, B, reg(in.c), n);
      break;
    case Op::constant:
      std::fill(r, r + n, in.k);
      break;
    case Op::x:
      std::copy(X, X + n, r);
      break;
    case Op::y:
      std::copy(Y, Y + n, r);
      break;
    case Op::z:
      std::copy(Z, Z + n, r);
      break;
    case Op::curve:
    case Op::curve_du:
    case Op::curve_dv:
      run_curve(in, r, A, B, n);
      break;
#define INTERLIN_CASE(o)                                                                           \
  case Op::o:                                                                                      \
    run_values<Op::o, N>(r, A, B, n, in.k);                                                        \
    break;
      INTERLIN_RF_VALUE_OPS(INTERLIN_CASE)
      INTERLIN_RF_IMMEDIATE_OPS(INTERLIN_CASE)
#undef INTERLIN_CASE
    }
  }
  const double* v = reg(p.out);
  for (int i = 0; i < n; ++i)
    out[i] = finite_value(v[i]);
}

// ---- dual-number kernel: each register holds the value and dF/dx, dF/dy, dF/dz ---------------

struct Dual {
  double* v;
  double* d[3];
};

template <Op O, int N>
void run_duals(const Dual& r, const Dual& A, const Dual& B, int n, double k) {
  const int len = N > 0 ? N : n;
  for (int i = 0; i < len; ++i) {
    const double a = A.v[i], b = B.v[i];
    const double v = detail::checked_value<O>(a, b, k);
    const detail::Partials pd = detail::partials<O>(a, b, v, k); // unary: b is a, ignored
    r.v[i] = v;
    for (int c = 0; c < 3; ++c)
      r.d[c][i] = pd.b == 0 ? pd.a * A.d[c][i] : pd.a * A.d[c][i] + pd.b * B.d[c][i];
  }
}

void dual_curve(const Instr& in, const Dual& r, const Dual& A, const Dual& B, int n) {
  for (int i = 0; i < n; ++i) {
    double du = 0, dv = 0;
    const double d = in.curve->signed_distance(A.v[i], B.v[i], &du, &dv);
    double pa = 0, pb = 0; // the distance's own second derivatives are taken as 0
    if (in.op == Op::curve) {
      r.v[i] = d;
      pa = du;
      pb = dv;
    } else {
      r.v[i] = in.op == Op::curve_du ? du : dv;
    }
    for (int c = 0; c < 3; ++c)
      r.d[c][i] = pa * A.d[c][i] + pb * B.d[c][i];
  }
}

void dual_field(const Instr& in, const Dual& r, const Dual& A, const Dual& B, const Dual& C,
                int n) {
  Eigen::VectorXd F;
  Points3 G;
  field_block(in, A.v, B.v, C.v, n, true, F, G);
  for (int i = 0; i < n; ++i) {
    if (in.op == Op::field) { // the body's own second derivatives are taken as 0
      r.v[i] = F(i);
      for (int c = 0; c < 3; ++c)
        r.d[c][i] = G(i, 0) * A.d[c][i] + G(i, 1) * B.d[c][i] + G(i, 2) * C.d[c][i];
    } else {
      r.v[i] = G(i, static_cast<int>(in.op) - static_cast<int>(Op::field_dx));
      for (int c = 0; c < 3; ++c)
        r.d[c][i] = 0;
    }
  }
}

template <int N>
void gradient_block(const Program& p, const double* const xyz[3], int n, double* regs, double* F,
                    double* G[3]) {
  const double *X = xyz[0], *Y = xyz[1], *Z = xyz[2];
  auto reg = [&](int s) {
    double* base = regs + static_cast<std::ptrdiff_t>(s) * 4 * kBlock;
    return Dual{base, {base + kBlock, base + 2 * kBlock, base + 3 * kBlock}};
  };
  for (const Instr& in : p.code) {
    const Dual r = reg(in.dst), A = reg(in.a), B = reg(in.b);
    switch (in.op) {
    case Op::field:
    case Op::field_dx:
    case Op::field_dy:
    case Op::field_dz:
      dual_field(in, r, A, B, reg(in.c), n);
      break;
    case Op::constant:
    case Op::x:
    case Op::y:
    case Op::z: {
      const double* src = in.op == Op::x ? X : in.op == Op::y ? Y : Z;
      if (in.op == Op::constant)
        std::fill(r.v, r.v + n, in.k);
      else
        std::copy(src, src + n, r.v);
      for (int c = 0; c < 3; ++c)
        std::fill(r.d[c], r.d[c] + n,
                  static_cast<int>(in.op) - static_cast<int>(Op::x) == c ? 1.0 : 0.0);
      break;
    }
    case Op::curve:
    case Op::curve_du:
    case Op::curve_dv:
      dual_curve(in, r, A, B, n);
      break;
#define INTERLIN_CASE(o)                                                                           \
  case Op::o:                                                                                      \
    run_duals<Op::o, N>(r, A, B, n, in.k);                                                         \
    break;
      INTERLIN_RF_VALUE_OPS(INTERLIN_CASE)
      INTERLIN_RF_IMMEDIATE_OPS(INTERLIN_CASE)
#undef INTERLIN_CASE
    }
  }
  const Dual o = reg(p.out);
  for (int i = 0; i < n; ++i) {
    F[i] = finite_value(o.v[i]);
    for (int c = 0; c < 3; ++c)
      G[c][i] = detail::is_finite(o.d[c][i]) ? o.d[c][i] : 0.0;
  }
}

// Register memory of the current thread, one buffer per nesting level: a program may evaluate a
// field that is itself a program, in the middle of a block.
class Scratch {
public:
  explicit Scratch(std::size_t size) : level_(depth()++) {
    std::vector<std::vector<double>>& pool = buffers();
    if (pool.size() <= level_)
      pool.resize(level_ + 1);
    if (pool[level_].size() < size)
      pool[level_].resize(size);
    data_ = pool[level_].data();
  }
  ~Scratch() { --depth(); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  double* data() const { return data_; }

private:
  static std::size_t& depth() {
    thread_local std::size_t d = 0;
    return d;
  }
  static std::vector<std::vector<double>>& buffers() {
    thread_local std::vector<std::vector<double>> b;
    return b;
  }
  std::size_t level_;
  double* data_;
};

void check_sizes(const char* what, Eigen::Index rows, Eigen::Index f_rows) {
  if (rows != f_rows)
    throw std::invalid_argument(std::string("ImplicitFunction::") + what + ": P has " +
                                std::to_string(rows) + " rows but F has " + std::to_string(f_rows));
}

// Column j of P (columns are contiguous: Points3 is column-major with unit inner stride).
const double* col(const Eigen::Ref<const Points3>& P, int j) {
  return P.data() + j * P.outerStride();
}

} // namespace

int operation_count(const Expr& F) {
  Linearizer lin;
  lin.visit(F.node());
  return static_cast<int>(lin.items.size());
}

ImplicitFunction compile(const Expr& F, const Eigen::AlignedBox3d& box) {
  auto prog = std::make_shared<const Program>(build_program(F.node()));
  ImplicitFunction f;
  f.box = box;
  f.value = [prog](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> out) {
    check_sizes("value", P.rows(), out.size());
    const Eigen::Index m = P.rows();
    const Scratch scratch(static_cast<std::size_t>(prog->slots) * kBlock);
    double* regs = scratch.data();
    for (Eigen::Index s = 0; s < m; s += kBlock) {
      const int n = static_cast<int>(std::min<Eigen::Index>(kBlock, m - s));
      const double* c[3] = {col(P, 0) + s, col(P, 1) + s, col(P, 2) + s};
      if (n == kBlock) // full blocks: loops of constant length, which the compiler vectorises
        evaluate_block<kBlock>(*prog, c, n, regs, out.data() + s);
      else
        evaluate_block<0>(*prog, c, n, regs, out.data() + s);
    }
  };
  f.gradient = [prog](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> out,
                      Eigen::Ref<Points3> G) {
    check_sizes("gradient", P.rows(), out.size());
    check_sizes("gradient", P.rows(), G.rows());
    const Eigen::Index m = P.rows();
    const Scratch scratch(static_cast<std::size_t>(prog->slots) * 4 * kBlock);
    double* regs = scratch.data();
    for (Eigen::Index s = 0; s < m; s += kBlock) {
      const int n = static_cast<int>(std::min<Eigen::Index>(kBlock, m - s));
      double* g[3] = {G.col(0).data() + s, G.col(1).data() + s, G.col(2).data() + s};
      const double* c[3] = {col(P, 0) + s, col(P, 1) + s, col(P, 2) + s};
      if (n == kBlock)
        gradient_block<kBlock>(*prog, c, n, regs, out.data() + s, g);
      else
        gradient_block<0>(*prog, c, n, regs, out.data() + s, g);
    }
  };
  return f;
}

} // namespace interlin::rf
