#include "ldlt_solve.h"

namespace posemorph::detail {

void SolvePinned(const Factor& f, const double* b, double* y, double* x) {
  const std::uint32_t n = f.n;
  const std::uint32_t* order = f.order.data;
  const std::uint32_t* col = f.col_start.data;
  const std::uint32_t* row = f.row.data;
  const double* L = f.value.data;

  for (std::uint32_t k = 0; k < n; ++k) {
    y[2 * k] = b[2 * order[k]];
    y[2 * k + 1] = b[2 * order[k] + 1];
  }
  // L z = P b, column by column; both coordinates share every index load.
  for (std::uint32_t j = 0; j < n; ++j) {
    const double zx = y[2 * j], zy = y[2 * j + 1];
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
      y[2 * row[q]] -= L[q] * zx;
      y[2 * row[q] + 1] -= L[q] * zy;
    }
  }
  for (std::uint32_t j = 0; j < n; ++j) {
    y[2 * j] *= f.inv_diagonal[j];
    y[2 * j + 1] *= f.inv_diagonal[j];
  }
  // L^T w = D^-1 z: column j of L is row j of L^T.
  for (std::uint32_t j = n; j-- > 0;) {
    double sx = y[2 * j], sy = y[2 * j + 1];
    for (std::uint32_t q = col[j]; q < col[j + 1]; ++q) {
      sx -= L[q] * y[2 * row[q]];
      sy -= L[q] * y[2 * row[q] + 1];
    }
    y[2 * j] = sx;
    y[2 * j + 1] = sy;
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    x[2 * order[k]] = y[2 * k];
    x[2 * order[k] + 1] = y[2 * k + 1];
  }
}

}  // namespace posemorph::detail
