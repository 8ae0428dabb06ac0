/*
 * test_human.h - the standard human, as the suites that solve, balance or
 * replay it build it: the male default, and its sites by name, failing the
 * test when either is missing. Include after <cmocka.h>.
 */
#ifndef POSTURE_TEST_HUMAN_H
#define POSTURE_TEST_HUMAN_H

#include "figure/human.h"
#include "figure/model.h"

static inline struct model *
test_human(void)
{
	char err[256];
	struct human_def d = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&d, err, sizeof err);
	assert_non_null(m);
	return m;
}

static inline int
test_site(const struct model *m, const char *name)
{
	int k = model_find_site(m, name);
	assert_true(k >= 0);
	return k;
}

#endif
