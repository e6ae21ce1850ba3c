#include "leadscrew/lcp/workspace.hpp"

#include <string>

#include "leadscrew/core/errors.hpp"

namespace leadscrew::lcp {

Workspace::Workspace(int capacity) {
  if (capacity < 0)
    throw InvalidArgument("capacity = " + std::to_string(capacity) +
                          " is invalid: must be an integer >= 0");
  allocate(capacity);
}

void Workspace::reserve(int n) {
  if (n > capacity_) allocate(n);
}

void Workspace::allocate(int capacity) {
  // Eigen's resize keeps no contents; nothing of a previous solve is needed.
  tableau.resize(capacity, capacity + 2);
  square.resize(capacity, capacity);
  vectors.resize(capacity, kVectorCount);
  indices.resize(6 * capacity + 4);
  permutation.resize(capacity);
  capacity_ = capacity;
}

}  // namespace leadscrew::lcp
