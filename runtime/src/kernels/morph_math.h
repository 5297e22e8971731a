// SPDX-License-Identifier: MIT
// The arithmetic of one frame, written once over T = double (one character)
// or T = Vec (kWidth characters sharing a rig, one per lane). Every lane
// performs exactly the operations a single evaluation performs, in the same
// order, so batched results equal single ones bit for bit, on every path.
// No include guard: included once per kernel translation unit, inside its
// namespace, after vec.h.

// Blended angle and stretch of one triangle: alpha with the raw weights w,
// S with the limited weights ws (DESIGN.md section 3).
template <typename T>
POSEMORPH_KERNEL_INLINE void BlendTriangle(const double* angle, const double* stretch, const T* w, const T* ws,
                                           std::uint32_t N, T* alpha, T* s11, T* s12, T* s22) {
  T a = w[0] * angle[0], b = ws[0] * stretch[0], c = ws[0] * stretch[1], d = ws[0] * stretch[2];
  for (std::uint32_t i = 1; i < N; ++i) {
    a += w[i] * angle[i];
    b += ws[i] * stretch[3 * i];
    c += ws[i] * stretch[3 * i + 1];
    d += ws[i] * stretch[3 * i + 2];
  }
  *alpha = a, *s11 = b, *s12 = c, *s22 = d;
}

// A = R(alpha) S.
template <typename T>
POSEMORPH_KERNEL_INLINE void TargetMatrix(T c, T s, T s11, T s12, T s22, T* a11, T* a12, T* a21, T* a22) {
  *a11 = c * s11 - s * s12;
  *a12 = c * s12 - s * s22;
  *a21 = s * s11 + c * s12;
  *a22 = s * s12 + c * s22;
}

// Row k of a triangle's gradient operator pulls vertex k by A's rows.
template <typename T>
POSEMORPH_KERNEL_INLINE void AddToRhs(const std::uint32_t* tri, const double* grad, T a11, T a12, T a21, T a22, T* b) {
  for (int k = 0; k < 3; ++k) {
    const double g0 = grad[2 * k], g1 = grad[2 * k + 1];
    b[2 * tri[k]] += g0 * a11 + g1 * a12;
    b[2 * tri[k] + 1] += g0 * a21 + g1 * a22;
  }
}

#if POSEMORPH_KERNEL_WIDTH > 1
// One character: the x and y rows as the two lanes of a pair, the same
// per-lane operations as the generic version.
template <>
POSEMORPH_KERNEL_INLINE void AddToRhs<double>(const std::uint32_t* tri, const double* grad, double a11, double a12,
                                              double a21, double a22, double* b) {
  typedef double Pair __attribute__((vector_size(16)));
  const Pair c0 = {a11, a21}, c1 = {a12, a22};
  for (int k = 0; k < 3; ++k) {
    const Pair g0 = {grad[2 * k], grad[2 * k]}, g1 = {grad[2 * k + 1], grad[2 * k + 1]};
    Pair v;
    std::memcpy(&v, b + 2 * tri[k], sizeof(v));
    v += g0 * c0 + g1 * c1;
    std::memcpy(b + 2 * tri[k], &v, sizeof(v));
  }
}
#endif

// s - sum_p l[p] * v[idx2[p] + d] for d = 0, 1 over p in [begin, end), in
// four interleaved partial sums: one running sum would chain every
// subtraction behind the previous one's latency, which is what bounded the
// solve (about 15 nonzeros per row).
template <typename T, typename I>
POSEMORPH_KERNEL_INLINE void GatherSubtract(const double* l, const I* idx2, std::uint32_t begin, std::uint32_t end,
                                            const T* v, T* sx, T* sy) {
  T x0 = *sx, y0 = *sy, x1 = T{}, y1 = x1, x2 = x1, y2 = x1, x3 = x1, y3 = x1;
  std::uint32_t p = begin;
  for (; p + 4 <= end; p += 4) {
    x0 -= l[p] * v[idx2[p]], y0 -= l[p] * v[idx2[p] + 1];
    x1 -= l[p + 1] * v[idx2[p + 1]], y1 -= l[p + 1] * v[idx2[p + 1] + 1];
    x2 -= l[p + 2] * v[idx2[p + 2]], y2 -= l[p + 2] * v[idx2[p + 2] + 1];
    x3 -= l[p + 3] * v[idx2[p + 3]], y3 -= l[p + 3] * v[idx2[p + 3] + 1];
  }
  for (; p < end; ++p) x0 -= l[p] * v[idx2[p]], y0 -= l[p] * v[idx2[p] + 1];
  *sx = (x0 + x1) + (x2 + x3);
  *sy = (y0 + y1) + (y2 + y3);
}

// K x = b for the n free unknowns (unknown k is vertex k + 1), both
// coordinates interleaved. y: 2n scratch. b and x may be the same array: b is
// read only in the forward pass, x written only in the backward one.
// Forward: z_i = b'_i - sum_j L_ij z_j over row i (gather, from the CSR copy).
// Backward: x_j = z_j / d_j - sum_i L_ij x_i over column j (gather, CSC).
template <typename T, typename I>
POSEMORPH_KERNEL_INLINE void SolvePinnedWith(const SolveLayout& f, const I* row_col2, const I* col_row2, const T* bf,
                                             T* y, T* xf) {
  const std::uint32_t n = f.n;
  const std::uint32_t* order = f.order.data;
  for (std::uint32_t i = 0; i < n; ++i) {
    T sx = bf[2 * order[i]], sy = bf[2 * order[i] + 1];
    GatherSubtract(f.row_value.data, row_col2, f.row_start[i], f.row_start[i + 1], y, &sx, &sy);
    y[2 * i] = sx, y[2 * i + 1] = sy;
  }
  for (std::uint32_t j = n; j-- > 0;) {
    T sx = y[2 * j] * f.inv_diagonal[j], sy = y[2 * j + 1] * f.inv_diagonal[j];
    GatherSubtract(f.value.data, col_row2, f.col_start[j], f.col_start[j + 1], y, &sx, &sy);
    y[2 * j] = sx, y[2 * j + 1] = sy;
    xf[2 * order[j]] = sx, xf[2 * order[j] + 1] = sy;
  }
}

template <typename T>
POSEMORPH_KERNEL_INLINE void SolvePinnedKernel(const SolveLayout& f, const T* bf, T* y, T* xf) {
  if (f.row_col2_16.size)
    SolvePinnedWith(f, f.row_col2_16.data, f.col_row2_16.data, bf, y, xf);
  else
    SolvePinnedWith(f, f.row_col2.data, f.col_row2.data, bf, y, xf);
}

// Moves the mass-weighted centroid of x (2V) to sum_i w_i c_i.
template <typename T>
POSEMORPH_KERNEL_INLINE void PlaceCentroid(const Rig& rig, const T* w, T* x) {
  const std::uint32_t V = rig.vertex_count(), N = rig.pose_count();
  const double* m = rig.vertex_masses().data;
  const double* c = rig.pose_centroids().data;
  // Four partial sums, for the same latency reason as GatherSubtract.
  T cx[4] = {T{}, T{}, T{}, T{}}, cy[4] = {T{}, T{}, T{}, T{}};
  for (std::uint32_t v = 0; v < V; ++v) {
    cx[v % 4] += m[v] * x[2 * v];
    cy[v % 4] += m[v] * x[2 * v + 1];
  }
  T tx = w[0] * c[0], ty = w[0] * c[1];
  for (std::uint32_t i = 1; i < N; ++i) {
    tx += w[i] * c[2 * i];
    ty += w[i] * c[2 * i + 1];
  }
  const T dx = tx - ((cx[0] + cx[1]) + (cx[2] + cx[3])), dy = ty - ((cy[0] + cy[1]) + (cy[2] + cy[3]));
  for (std::uint32_t v = 0; v < V; ++v) {
    x[2 * v] += dx;
    x[2 * v + 1] += dy;
  }
}
