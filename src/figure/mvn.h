/*
 * mvn.h - the arithmetic of the multivariate normal that populations need:
 * Cholesky factors and solves, the eigen decomposition of a symmetric
 * matrix, and the chi-square distribution and its quantile.
 *
 * Matrices are row-major n x n. No allocation; nothing here reads a clock
 * or does I/O.
 */
#ifndef POSTURE_MVN_H
#define POSTURE_MVN_H

/*
 * Factors the symmetric positive definite a (n x n) in place into its
 * lower Cholesky factor L (a = L L^T; the strict upper triangle is zeroed).
 * Returns 0, or -1 when a is not positive definite: a pivot at or below
 * 1e-10 times its diagonal element (linearly dependent rows) or not finite.
 */
int mvn_cholesky(double *a, int n);

/* solves L L^T x = b in place (b becomes x) with L from mvn_cholesky */
void mvn_cholesky_solve(const double *l, int n, double *b);

/*
 * The eigenvalues and eigenvectors of the symmetric a (n x n; destroyed),
 * by cyclic Jacobi rotations: evals descending, evecs (n x n) holding the
 * unit eigenvector of evals[i] in column i, its largest component
 * positive (so the result does not depend on rounding's whims).
 * Returns 0, or -1 when the sweeps did not converge (non-finite input).
 */
int mvn_eigen(double *a, int n, double *evals, double *evecs);

/* the regularized lower incomplete gamma function P(a, x), a > 0, x >= 0 */
double mvn_gamma_p(double a, double x);

/* the chi-square distribution function with k degrees of freedom at x */
double mvn_chi2_cdf(double x, int k);

/*
 * The chi-square quantile: the x with mvn_chi2_cdf(x, k) = p, for
 * 0 < p < 1 and k >= 1 (NaN otherwise). Wilson-Hilferty's cube-root
 * normal approximation starts Newton's method on the distribution
 * function, safeguarded by bisection; relative accuracy about 1e-13.
 */
double mvn_chi2_quantile(double p, int k);

#endif
