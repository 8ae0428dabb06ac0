/* ik_metric.c - the variable metric: identity, BFGS update, Gauss-Newton inverse */
#include "pose/ik_metric.h"

#include <math.h>
#include <string.h>

void
ik_metric_reset(int n, double scale, double *dest)
{
	memset(dest, 0, sizeof *dest * (size_t)n * (size_t)n);
	for (int i = 0; i < n; i++)
		dest[i * n + i] = scale;
}

void
ik_metric_bfgs(int n, const double *s, const double *y, double sy, double *hy, double *dest)
{
	double *H = dest, yhy = 0;
	for (int i = 0; i < n; i++) {
		double acc = 0;
		for (int j = 0; j < n; j++)
			acc += H[i * n + j] * y[j];
		hy[i] = acc;
		yhy += y[i] * acc;
	}
	double a = (sy + yhy) / (sy * sy), b = 1 / sy;
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++)
			H[i * n + j] += a * s[i] * s[j] - b * (hy[i] * s[j] + s[i] * hy[j]);
}

int
ik_metric_invert(int n, double *B, const unsigned char *pin, double *L, int *free_idx,
		 double *dest)
{
	double *H = dest, dmax = 0;
	int nf = 0;
	for (int i = 0; i < n; i++)
		if (!pin[i])
			free_idx[nf++] = i;
	for (int i = 0; i < nf; i++)
		dmax = fmax(dmax, B[free_idx[i] * n + free_idx[i]]);
	double mu = 1e-6 * dmax + 1e-12;
	/* L L^T of the free block, packed nf x nf in the lower triangle */
	for (int i = 0; i < nf; i++) {
		for (int j = 0; j <= i; j++) {
			double acc = B[free_idx[i] * n + free_idx[j]] + (i == j ? mu : 0);
			for (int k = 0; k < j; k++)
				acc -= L[i * nf + k] * L[j * nf + k];
			if (i == j) {
				if (acc <= 0)
					return -1;
				L[i * nf + i] = sqrt(acc);
			} else {
				L[i * nf + j] = acc / L[j * nf + j];
			}
		}
	}
	/* M = L^-T row by row (row c of M is column c of L^-1: zero before c),
	 * over B, which is spent; then H = M M^T. Rows keep the loops contiguous. */
	double *M = B;
	for (int c = 0; c < nf; c++) {
		double *mc = &M[c * nf];
		memset(mc, 0, sizeof *mc * (size_t)c);
		mc[c] = 1 / L[c * nf + c];
		for (int i = c + 1; i < nf; i++) {
			const double *li = &L[i * nf];
			double acc = 0;
			for (int k = c; k < i; k++)
				acc -= li[k] * mc[k];
			mc[i] = acc / li[i];
		}
	}
	memset(H, 0, sizeof *H * (size_t)n * (size_t)n);
	for (int i = 0; i < nf; i++)
		for (int j = 0; j <= i; j++) {
			const double *mi = &M[i * nf], *mj = &M[j * nf];
			double acc = 0;
			for (int k = i; k < nf; k++)
				acc += mi[k] * mj[k];
			H[free_idx[i] * n + free_idx[j]] = H[free_idx[j] * n + free_idx[i]] = acc;
		}
	return 0;
}
