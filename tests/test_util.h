/*
 * test_util.h - what cmocka lacks: a comparison of doubles in double
 * precision (cmocka's assert_float_equal casts to float, so a 1e-12
 * tolerance would quietly become about 1e-7 relative). Include after
 * <cmocka.h>.
 */
#ifndef POSTURE_TEST_UTIL_H
#define POSTURE_TEST_UTIL_H

#include <math.h>

#define assert_near(a, b, tol) test_near_at((a), (b), (tol), #a, __FILE__, __LINE__)

static inline void
test_near_at(double a, double b, double tol, const char *what, const char *file, int line)
{
	if (!(fabs(a - b) <= tol))
		fail_msg("%s:%d: %s = %.17g, want %.17g (tolerance %g)", file, line, what, a, b,
			 tol);
}

#endif
