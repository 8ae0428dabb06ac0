/* mvn.c - Cholesky, Jacobi eigenvalues and the chi-square quantile */
#include "figure/mvn.h"

#include <float.h>
#include <math.h>
#include <string.h>

int
mvn_cholesky(double *a, int n)
{
	for (int j = 0; j < n; j++) {
		double diag = a[j * n + j], s = diag;
		for (int k = 0; k < j; k++)
			s -= a[j * n + k] * a[j * n + k];
		/* a pivot lost to cancellation: the row depends on those above it */
		if (!(s > 1e-10 * diag) || !isfinite(s))
			return -1;
		double d = sqrt(s);
		a[j * n + j] = d;
		for (int i = j + 1; i < n; i++) {
			double t = a[i * n + j];
			for (int k = 0; k < j; k++)
				t -= a[i * n + k] * a[j * n + k];
			a[i * n + j] = t / d;
		}
		for (int k = j + 1; k < n; k++)
			a[j * n + k] = 0;
	}
	return 0;
}

void
mvn_cholesky_solve(const double *l, int n, double *b)
{
	/* L y = b, then L^T x = y */
	for (int i = 0; i < n; i++) {
		double t = b[i];
		for (int k = 0; k < i; k++)
			t -= l[i * n + k] * b[k];
		b[i] = t / l[i * n + i];
	}
	for (int i = n - 1; i >= 0; i--) {
		double t = b[i];
		for (int k = i + 1; k < n; k++)
			t -= l[k * n + i] * b[k];
		b[i] = t / l[i * n + i];
	}
}

/* one Jacobi rotation zeroing a[p][q], applied to a and accumulated in v */
static void
rotate(double *a, double *v, int n, int p, int q)
{
	double apq = a[p * n + q];
	double theta = (a[q * n + q] - a[p * n + p]) / (2 * apq);
	double t = (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
	double c = 1 / sqrt(t * t + 1), s = t * c;
	for (int k = 0; k < n; k++) {
		double akp = a[k * n + p], akq = a[k * n + q];
		a[k * n + p] = c * akp - s * akq;
		a[k * n + q] = s * akp + c * akq;
	}
	for (int k = 0; k < n; k++) {
		double apk = a[p * n + k], aqk = a[q * n + k];
		a[p * n + k] = c * apk - s * aqk;
		a[q * n + k] = s * apk + c * aqk;
	}
	for (int k = 0; k < n; k++) {
		double vkp = v[k * n + p], vkq = v[k * n + q];
		v[k * n + p] = c * vkp - s * vkq;
		v[k * n + q] = s * vkp + c * vkq;
	}
}

int
mvn_eigen(double *a, int n, double *evals, double *evecs)
{
	for (int i = 0; i < n * n; i++)
		evecs[i] = i % (n + 1) == 0;
	double norm = 0;
	for (int i = 0; i < n * n; i++)
		norm += a[i] * a[i];
	if (!isfinite(norm))
		return -1;
	int converged = 0;
	for (int sweep = 0; sweep < 100 && !converged; sweep++) {
		double off = 0;
		for (int p = 0; p < n; p++)
			for (int q = p + 1; q < n; q++)
				off += a[p * n + q] * a[p * n + q];
		if (off <= DBL_EPSILON * DBL_EPSILON * norm) {
			converged = 1;
			break;
		}
		for (int p = 0; p < n; p++)
			for (int q = p + 1; q < n; q++)
				if (a[p * n + q] != 0)
					rotate(a, evecs, n, p, q);
	}
	if (!converged)
		return -1;
	for (int i = 0; i < n; i++)
		evals[i] = a[i * n + i];
	/* descending, by selection: n is small */
	for (int i = 0; i < n; i++) {
		int best = i;
		for (int j = i + 1; j < n; j++)
			if (evals[j] > evals[best])
				best = j;
		if (best != i) {
			double t = evals[i];
			evals[i] = evals[best];
			evals[best] = t;
			for (int k = 0; k < n; k++) {
				t = evecs[k * n + i];
				evecs[k * n + i] = evecs[k * n + best];
				evecs[k * n + best] = t;
			}
		}
	}
	/* each vector's largest component positive: a sign independent of rounding */
	for (int i = 0; i < n; i++) {
		int big = 0;
		for (int k = 1; k < n; k++)
			if (fabs(evecs[k * n + i]) > fabs(evecs[big * n + i]) + 1e-12)
				big = k;
		if (evecs[big * n + i] < 0)
			for (int k = 0; k < n; k++)
				evecs[k * n + i] = -evecs[k * n + i];
	}
	return 0;
}

double
mvn_gamma_p(double a, double x)
{
	if (!(a > 0) || !(x >= 0))
		return NAN;
	if (x == 0)
		return 0;
	double lead = exp(-x + a * log(x) - lgamma(a));
	if (x < a + 1) {
		/* the series x^a e^-x / Gamma(a + 1) * (1 + x/(a+1) + x^2/((a+1)(a+2)) + ...) */
		double term = 1 / a, sum = term;
		for (int i = 1; i < 1000; i++) {
			term *= x / (a + i);
			sum += term;
			if (fabs(term) < fabs(sum) * DBL_EPSILON)
				break;
		}
		return fmin(1, sum * lead);
	}
	/* Q(a, x) by its continued fraction, evaluated with Lentz's method */
	const double tiny = 1e-300;
	double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
	for (int i = 1; i < 1000; i++) {
		double an = -i * (i - a);
		b += 2;
		d = an * d + b;
		if (fabs(d) < tiny)
			d = tiny;
		c = b + an / c;
		if (fabs(c) < tiny)
			c = tiny;
		d = 1 / d;
		double delta = d * c;
		h *= delta;
		if (fabs(delta - 1) < DBL_EPSILON)
			break;
	}
	return fmax(0, 1 - lead * h);
}

double
mvn_chi2_cdf(double x, int k)
{
	if (k < 1 || isnan(x))
		return NAN;
	return x <= 0 ? 0 : mvn_gamma_p(0.5 * k, 0.5 * x);
}

/* the chi-square density with k degrees of freedom at x > 0 */
static double
chi2_pdf(double x, int k)
{
	double h = 0.5 * k;
	return exp((h - 1) * log(x) - 0.5 * x - h * log(2.0) - lgamma(h));
}

/*
 * The standard normal quantile to about 4.5e-4 (Abramowitz & Stegun 1964,
 * 26.2.23): only Newton's starting point depends on it.
 */
static double
normal_quantile_rough(double p)
{
	double q = p < 0.5 ? p : 1 - p;
	double t = sqrt(-2 * log(q));
	double z = t - (2.515517 + t * (0.802853 + t * 0.010328)) /
			       (1 + t * (1.432788 + t * (0.189269 + t * 0.001308)));
	return p < 0.5 ? -z : z;
}

double
mvn_chi2_quantile(double p, int k)
{
	if (!(p > 0 && p < 1) || k < 1)
		return NAN;
	/* Wilson-Hilferty: (X/k)^(1/3) is nearly normal, mean 1 - 2/(9k), variance 2/(9k) */
	double v = 2.0 / (9.0 * k), z = normal_quantile_rough(p);
	double w = 1 - v + z * sqrt(v);
	double x = w > 0.05 ? k * w * w * w : 0.5 * k * p; /* the far lower tail: a small start */
	/* a bracket [lo, hi] around the root, Newton inside it, bisection when Newton leaves it */
	double lo = 0, hi = fmax(x, 1.0);
	while (mvn_chi2_cdf(hi, k) < p)
		hi *= 2;
	for (int i = 0; i < 200; i++) {
		double f = mvn_chi2_cdf(x, k) - p;
		if (f == 0)
			return x;
		if (f < 0)
			lo = x;
		else
			hi = x;
		double d = chi2_pdf(x, k);
		double next = d > 0 ? x - f / d : 0.5 * (lo + hi);
		if (!(next > lo && next < hi))
			next = 0.5 * (lo + hi);
		if (fabs(next - x) <= 4 * DBL_EPSILON * x || hi - lo <= 4 * DBL_EPSILON * hi)
			return next;
		x = next;
	}
	return x;
}
