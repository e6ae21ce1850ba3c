// Preallocated scratch shared by every LCP method (Pinocchio-style "Data").
//
// A Workspace built with capacity c solves any problem of size n <= c without
// touching the heap; a larger problem grows it once (one allocation per
// buffer), after which that size is again allocation-free. One Workspace must
// not be used by two solves at the same time.
#pragma once

#include <Eigen/Core>

namespace leadscrew::lcp {

class Workspace {
 public:
  static constexpr int kDefaultCapacity = 16;
  // Scratch vectors available to a method (columns of `vectors`).
  static constexpr int kVectorCount = 8;

  explicit Workspace(int capacity = kDefaultCapacity);  // InvalidArgument if capacity < 0

  int capacity() const noexcept { return capacity_; }
  // Make room for problems of size n; allocates only when n > capacity().
  void reserve(int n);

  // Scratch, contents unspecified between calls (public so that the one
  // source file per method can use it without accessors):
  Eigen::MatrixXd tableau;      // capacity x (capacity + 2): Lemke's condensed tableau
  Eigen::MatrixXd square;       // capacity x capacity: Jacobians, principal submatrices, LU,
                                // Lemke's pending pivots
  Eigen::MatrixXd vectors;      // capacity x kVectorCount scratch vectors
  Eigen::VectorXi indices;      // 6 capacity + 4: Lemke's basis bookkeeping, index sets
  Eigen::VectorXi permutation;  // capacity: LU row interchanges

 private:
  void allocate(int capacity);
  int capacity_ = 0;
};

}  // namespace leadscrew::lcp
