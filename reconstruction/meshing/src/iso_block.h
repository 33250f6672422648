#pragma once
// Internal: marching cubes on one block of grid nodes, and the exact merge of block meshes along
// the grid planes they share (seed 002's sub-box scheme).

#include "interlin/reconstruction/meshing/marching_cubes.h"

#include <Eigen/Core>
#include <algorithm>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace interlin::detail {

// A growable array of a trivially copyable type on malloc/realloc: large blocks grow by page
// remapping instead of copying, and appends need no per-element bookkeeping beyond the size.
template <class T>
class PodBuffer {
  static_assert(std::is_trivially_copyable_v<T>);

public:
  PodBuffer() = default;
  PodBuffer(const PodBuffer&) = delete;
  PodBuffer& operator=(const PodBuffer&) = delete;
  PodBuffer(PodBuffer&& o) noexcept { swap(o); }
  PodBuffer& operator=(PodBuffer&& o) noexcept {
    swap(o);
    return *this;
  }
  ~PodBuffer() { std::free(data_); }
  void swap(PodBuffer& o) noexcept {
    std::swap(data_, o.data_), std::swap(size_, o.size_), std::swap(cap_, o.cap_);
  }
  size_t size() const { return size_; }
  const T* data() const { return data_; }
  const T& operator[](size_t i) const { return data_[i]; }
  void clear() { size_ = 0; }
  // Room for n more elements; returns where they go (commit them with `added`).
  T* extend(size_t n) {
    if (size_ + n > cap_) {
      const size_t cap = std::max({size_ + n, 2 * cap_, size_t(4096)});
      T* p = static_cast<T*>(std::realloc(data_, cap * sizeof(T)));
      if (!p)
        throw std::bad_alloc();
      data_ = p, cap_ = cap;
    }
    return data_ + size_;
  }
  void added(size_t n) { size_ += n; }

private:
  T* data_ = nullptr;
  size_t size_ = 0, cap_ = 0;
};

struct BlockMesh {
  PodBuffer<double> V; // 3 per vertex
  PodBuffer<int> F;    // 3 per triangle, block-local vertex indices
  // Per vertex, when asked for: grid edge 3 * node + axis, and the values at its two nodes.
  std::vector<long> key;
  std::vector<double> ends;
  // Vertices on a block face shared with another block: (local index, grid edge key).
  std::vector<std::pair<int, long>> shared;
  long vertices() const { return long(V.size() / 3); }
};

// Marching cubes on the nodes [lo, lo + n) of g (n >= 2 on every axis), whose values are
// s[i + sy * j + sz * k] for the local node (i, j, k). `out` is overwritten; with `ends` the
// edge end values are kept for projection.
void extract_block(const RegularGrid& g, const double* s, long sy, long sz,
                   const Eigen::Array3i& lo, const Eigen::Array3i& n, bool ends, BlockMesh& out);

// Concatenates the blocks in order; a vertex on a shared face appears once (the first block's
// copy; the copies are bit-identical because both blocks interpolate the same two node values).
// E is filled when given (the blocks must then hold `ends`). Copies run on `threads` workers.
void merge_blocks(const std::vector<BlockMesh>& blocks, Eigen::MatrixXd& V, Eigen::MatrixXi& F,
                  std::vector<EdgeVertex>* E, int threads);

} // namespace interlin::detail
