/*
 * test_random.h - the seeded random inputs the geometry suites share:
 * splitmix64, so a failing trial replays from its seed, and the uniform
 * numbers and vectors built on it. Each suite sets rng_state to its own
 * seed at the start of a test. Include after <cmocka.h>.
 */
#ifndef POSTURE_TEST_RANDOM_H
#define POSTURE_TEST_RANDOM_H

#include <math.h>
#include <stdint.h>

#include "figure/mathx.h"

/* one generator per suite (static: each test program has its own) */
static uint64_t rng_state;

/* uniform in [0, 1) */
static inline double
urand(void)
{
	uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	z ^= z >> 31;
	return (double)(z >> 11) / 9007199254740992.0;
}

/* uniform in [lo, hi) */
static inline double
span(double lo, double hi)
{
	return lo + (hi - lo) * urand();
}

static inline void
rand_vec(double lo, double hi, double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = span(lo, hi);
}

/* a unit vector, uniform on the sphere (rejection from the unit ball, away from its centre) */
static inline void
rand_unit(double dest[3])
{
	double v[3];
	do
		rand_vec(-1, 1, v);
	while (mathx_dot(v, v) < 0.01 || mathx_dot(v, v) > 1);
	double n = sqrt(mathx_dot(v, v));
	for (int i = 0; i < 3; i++)
		dest[i] = v[i] / n;
}

#endif
