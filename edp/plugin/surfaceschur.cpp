// Sparse Cholesky (CHOLMOD) of the elastic stiffness K with the contact
// surface's u_z dofs J ordered last, for the 3D Newton systems
//   (P K P + D + C) x = b
// whose C (the contact Jacobian) and P, D (held dofs of exact contact) touch
// only J. With J last, L = [L_II 0; L_JI L_JJ] and the Schur complement of K on
// J is S = L_JJ L_JJ^T: a new active set changes only the dense m x m system
// S + C_JJ (restricted to J's free dofs), so a level factorizes K once and
// every step is an exact solve: one sparse forward and backward substitution
// around a dense one. Measured on the 3D ellipsoid's fine level (66k dofs,
// m = 1068): the factorization costs 1.2 times one of K + C in METIS's
// order, a dense Cholesky of S + C_JJ 0.03 s, a solve as much as CHOLMOD's.
//   surfaceSchurFactor(K, J)         K: half storage (sym=1); J: the dofs kept last
//   surfaceSchurSystem(C, mask, D)   C: nonzero on J x J only (or empty); mask: 0 at held dofs, D there
//   surfaceSchurSolve(b, x)          x = the system's solution
// Each returns 0, or a code: 1 CHOLMOD failed (not positive definite), 2 C
// reaches outside J x J, 3 the dense system is not positive definite, 4
// called out of order.
#include "ff++.hpp"
#include <cholmod.h>
#include <vector>
#include <cstring>

extern "C" {
void dpotrf_(const char *, const int *, double *, const int *, int *);
void dsyrk_(const char *, const char *, const int *, const int *, const double *, const double *,
            const int *, const double *, double *, const int *);
void dtrmv_(const char *, const char *, const char *, const int *, const double *, const int *,
            double *, const int *);
void dtrsv_(const char *, const char *, const char *, const int *, const double *, const int *,
            double *, const int *);
}

namespace {
struct State {
  cholmod_common common;
  bool started = false;
  cholmod_factor *L = nullptr;
  int n = 0, m = 0;
  std::vector<int> J, posJ;        // J (original dofs), and each dof's place in J (-1 outside)
  std::vector<double> LJJ, S;      // column-major m x m, lower
  std::vector<int> freeJ;          // places in J of the free dofs of the current system
  std::vector<double> M;           // Cholesky factor of (S + C_JJ) on them
  std::vector<double> heldDiag;    // D at the held dofs (by place in J), 0 where free
  bool factored = false, system = false;
} st;

void release() {
  if (st.L) cholmod_free_factor(&st.L, &st.common);
  st.factored = st.system = false;
}

// K (FreeFEM's hash matrix, half or full storage) as CHOLMOD's lower triangle
cholmod_sparse *lowerOf(MatriceMorse<double> &A) {
  cholmod_triplet *T = cholmod_allocate_triplet(A.n, A.n, A.nnz, -1, CHOLMOD_REAL, &st.common);
  int *I = (int *)T->i, *Jt = (int *)T->j;
  double *X = (double *)T->x;
  long k = 0;
  for (long e = 0; e < A.nnz; e++) {
    int i = A.i[e], j = A.j[e];
    if (i < j) {
      if (!A.half) continue;  // full storage: the lower entry is there too
      std::swap(i, j);
    }
    I[k] = i; Jt[k] = j; X[k] = A.aij[e]; k++;
  }
  T->nnz = k;
  cholmod_sparse *S = cholmod_triplet_to_sparse(T, k, &st.common);
  cholmod_free_triplet(&T, &st.common);
  return S;
}
}  // namespace

long surfaceSchurFactor(Matrice_Creuse<double> *const &pK, KN<long> *const &pJ) {
  if (!st.started) { cholmod_start(&st.common); st.started = true; }
  release();
  MatriceCreuse<double> *pa = pK->A;
  MatriceMorse<double> *pA = dynamic_cast<MatriceMorse<double> *>(pa);
  if (!pA) return 4;
  cholmod_common &c = st.common;
  int n = pA->n, m = pJ->N();
  st.n = n; st.m = m;
  st.J.assign(m, 0); st.posJ.assign(n, -1);
  for (int q = 0; q < m; q++) { st.J[q] = (int)(*pJ)[q]; st.posJ[st.J[q]] = q; }
  cholmod_sparse *K = lowerOf(*pA);
  // the order: METIS's on K's node graph (the dofs of a node share their
  // pattern: 3 times fewer vertices, the ordering in half the time at 66k
  // dofs), each node's dofs outside J in it, then J (kept last: no postordering)
  cholmod_sparse *Kfull = cholmod_copy(K, 0, 1, &c);
  cholmod_sort(Kfull, &c);
  const int *p = (const int *)Kfull->p, *r = (const int *)Kfull->i;
  std::vector<int> group(n), first;
  for (int j = 0; j < n; j++) {
    int a = j - 1;
    if (j > 0 && p[a + 1] - p[a] == p[j + 1] - p[j]
        && std::memcmp(r + p[a], r + p[j], (p[j + 1] - p[j]) * sizeof(int)) == 0) { group[j] = group[a]; continue; }
    group[j] = first.size();
    first.push_back(j);
  }
  int ng = first.size();
  cholmod_sparse *G = cholmod_allocate_sparse(ng, ng, p[n], 1, 1, -1, CHOLMOD_PATTERN, &c);
  int *gp = (int *)G->p, *gi = (int *)G->i;
  std::vector<int> mark(ng, -1);
  long nz = 0;
  for (int g = 0; g < ng; g++) {
    gp[g] = nz;
    for (int k = p[first[g]]; k < p[first[g] + 1]; k++) {
      int h = group[r[k]];
      if (h >= g && mark[h] != g) { mark[h] = g; gi[nz++] = h; }
    }
  }
  gp[ng] = nz;
  cholmod_free_sparse(&Kfull, &c);
  std::vector<int> perm(n), pg(ng);
  int ok = cholmod_metis(G, nullptr, 0, 1, pg.data(), &c);
  cholmod_free_sparse(&G, &c);
  if (!ok) { cholmod_free_sparse(&K, &c); return 1; }
  int k = 0;
  for (int a = 0; a < ng; a++)
    for (int j = first[pg[a]]; j < n && group[j] == pg[a]; j++)
      if (st.posJ[j] < 0) perm[k++] = j;
  for (int q = 0; q < m; q++) perm[n - m + q] = st.J[q];
  c.nmethods = 1; c.method[0].ordering = CHOLMOD_GIVEN; c.postorder = 0;
  c.supernodal = CHOLMOD_SUPERNODAL;  // LL' in supernodes at every size: the extraction below reads them
  st.L = cholmod_analyze_p(K, perm.data(), nullptr, 0, &c);
  if (!st.L) { cholmod_free_sparse(&K, &c); return 1; }
  cholmod_factorize(K, st.L, &c);
  cholmod_free_sparse(&K, &c);
  if (c.status != CHOLMOD_OK || st.L->minor < (size_t)n || !st.L->is_super) { release(); return 1; }
  int *order = (int *)st.L->Perm;  // J must have stayed last
  for (int q = n - m; q < n; q++) if (st.posJ[order[q]] < 0) { release(); return 1; }
  // L_JJ: the trailing m columns, all inside the last supernodes
  int n0 = n - m;
  st.LJJ.assign((size_t)m * m, 0.);
  int *Super = (int *)st.L->super, *Pi = (int *)st.L->pi, *Ls = (int *)st.L->s;
  int *Px = (int *)st.L->px;
  double *Lx = (double *)st.L->x;
  for (size_t s = 0; s < st.L->nsuper; s++) {
    int k1 = Super[s], k2 = Super[s + 1];
    if (k2 <= n0) continue;
    int nsrow = Pi[s + 1] - Pi[s];
    for (int col = std::max(k1, n0); col < k2; col++)
      for (int r = 0; r < nsrow; r++) {
        int row = Ls[Pi[s] + r];
        if (row < col) continue;
        st.LJJ[(size_t)(col - n0) * m + (row - n0)] = Lx[Px[s] + (size_t)(col - k1) * nsrow + r];
      }
  }
  st.S.assign((size_t)m * m, 0.);
  const double one = 1., zero = 0.;
  dsyrk_("L", "N", &m, &m, &one, st.LJJ.data(), &m, &zero, st.S.data(), &m);
  st.factored = true;
  return 0;
}

long surfaceSchurSystem(Matrice_Creuse<double> *const &pC, KN<double> *const &pMask, KN<double> *const &pD) {
  if (!st.factored) return 4;
  int m = st.m;
  st.system = false;
  std::vector<int> place(m, -1);
  st.freeJ.clear();
  st.heldDiag.assign(m, 0.);
  for (int q = 0; q < m; q++) {
    int i = st.J[q];
    if ((*pMask)[i] != 0) { place[q] = st.freeJ.size(); st.freeJ.push_back(q); }
    else st.heldDiag[q] = (*pD)[i];
  }
  int mf = st.freeJ.size();
  st.M.assign((size_t)mf * mf, 0.);
  for (int b = 0; b < mf; b++)
    for (int a = b; a < mf; a++) st.M[(size_t)b * mf + a] = st.S[(size_t)st.freeJ[b] * m + st.freeJ[a]];
  MatriceCreuse<double> *pc = pC->A;
  MatriceMorse<double> *pA = pc ? dynamic_cast<MatriceMorse<double> *>(pc) : nullptr;
  if (pA && pA->n > 0) {
    MatriceMorse<double> &A = *pA;
    for (long e = 0; e < A.nnz; e++) {
      double v = A.aij[e];
      if (v == 0) continue;
      int i = A.i[e], j = A.j[e];
      if (i >= st.n || j >= st.n || st.posJ[i] < 0 || st.posJ[j] < 0) return 2;
      if (!A.half && i < j) continue;
      int a = place[st.posJ[i]], b = place[st.posJ[j]];
      if (a < 0 || b < 0) continue;  // a held row: D alone
      if (a < b) std::swap(a, b);
      st.M[(size_t)b * mf + a] += v;
    }
  }
  int info = 0;
  if (mf > 0) dpotrf_("L", &mf, st.M.data(), &mf, &info);
  if (info != 0) return 3;
  st.system = true;
  return 0;
}

long surfaceSchurSolve(KN<double> *const &pb, KN<double> *const &px) {
  if (!st.system) return 4;
  cholmod_common &c = st.common;
  int n = st.n, m = st.m, n0 = n - m, mf = st.freeJ.size(), inc = 1;
  cholmod_dense *b = cholmod_zeros(n, 1, CHOLMOD_REAL, &c);
  double *bx = (double *)b->x;
  for (int i = 0; i < n; i++) bx[i] = (*pb)[i];
  for (int q = 0; q < m; q++) if (st.heldDiag[q] != 0) bx[st.J[q]] = 0;  // held: D x = b alone
  cholmod_dense *y = cholmod_solve(CHOLMOD_P, st.L, b, &c);
  cholmod_dense *y2 = cholmod_solve(CHOLMOD_L, st.L, y, &c);
  double *yv = (double *)y2->x;
  // g = L_JJ y_J = b_J - L_JI y_I; then (S + C)_ff x_f = g_f
  std::vector<double> g(yv + n0, yv + n);
  dtrmv_("L", "N", "N", &m, st.LJJ.data(), &m, g.data(), &inc);
  std::vector<double> xf(mf), xJ(m, 0.);
  for (int a = 0; a < mf; a++) xf[a] = g[st.freeJ[a]];
  if (mf > 0) {
    dtrsv_("L", "N", "N", &mf, st.M.data(), &mf, xf.data(), &inc);
    dtrsv_("L", "T", "N", &mf, st.M.data(), &mf, xf.data(), &inc);
  }
  for (int a = 0; a < mf; a++) xJ[st.freeJ[a]] = xf[a];
  // back substitution through L^T with w_J = L_JJ^T x_J: gives x_I = K_II^-1 (b_I - K_IJ x_J)
  std::vector<double> w(xJ);
  dtrmv_("L", "T", "N", &m, st.LJJ.data(), &m, w.data(), &inc);
  for (int q = 0; q < m; q++) yv[n0 + q] = w[q];
  cholmod_dense *z = cholmod_solve(CHOLMOD_Lt, st.L, y2, &c);
  cholmod_dense *x = cholmod_solve(CHOLMOD_Pt, st.L, z, &c);
  double *xv = (double *)x->x;
  px->resize(n);
  for (int i = 0; i < n; i++) (*px)[i] = xv[i];
  for (int q = 0; q < m; q++) if (st.heldDiag[q] != 0) (*px)[st.J[q]] = (*pb)[st.J[q]] / st.heldDiag[q];
  cholmod_free_dense(&b, &c); cholmod_free_dense(&y, &c); cholmod_free_dense(&y2, &c);
  cholmod_free_dense(&z, &c); cholmod_free_dense(&x, &c);
  return 0;
}

static void Load_Init() {
  Global.Add("surfaceSchurFactor", "(", new OneOperator2_<long, Matrice_Creuse<double> *, KN<long> *>(surfaceSchurFactor));
  Global.Add("surfaceSchurSystem", "(",
             new OneOperator3_<long, Matrice_Creuse<double> *, KN<double> *, KN<double> *>(surfaceSchurSystem));
  Global.Add("surfaceSchurSolve", "(", new OneOperator2_<long, KN<double> *, KN<double> *>(surfaceSchurSolve));
}
LOADFUNC(Load_Init)
