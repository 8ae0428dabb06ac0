/*
 * fk_human - forward kinematics + centre of mass of the standard human.
 *
 * usage: fk_human [Q_FILE]
 * Evaluates kin_update (global frames of every segment and site, dof axes,
 * sub-tree and whole-body centres of mass) over a set of postures: the
 * lines of Q_FILE (every dof value in order), or 1000 random postures
 * within the limits. Prints the median over batches of the time per
 * evaluation as "BENCH fk.human.posture us=...".
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "figure/human.h"
#include "figure/kin.h"

#define BATCHES 31
#define MAX_POSTURES 4096



static int
load_postures(const char *path, int ndof, double *q)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		perror(path);
		return -1;
	}
	int n = 0;
	while (n < MAX_POSTURES) {
		int d;
		for (d = 0; d < ndof; d++)
			if (fscanf(f, "%lf", &q[(size_t)n * ndof + d]) != 1)
				break;
		if (d == 0)
			break;
		if (d != ndof) {
			fprintf(stderr, "%s: posture %d has %d of %d values\n", path, n + 1, d, ndof);
			fclose(f);
			return -1;
		}
		n++;
	}
	fclose(f);
	return n;
}

int
main(int argc, char **argv)
{
	char err[256];
	struct human_def def = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&def, err, sizeof err);
	if (!m) {
		fprintf(stderr, "fk_human: %s\n", err);
		return 1;
	}
	struct state *s = state_make(m);
	kin_update(m, s);
	double *q = malloc(sizeof *q * (size_t)m->ndof * MAX_POSTURES);
	int n = 1000;
	if (argc > 1) {
		n = load_postures(argv[1], m->ndof, q);
		if (n <= 0)
			return 1;
	} else {
		srand(1);
		for (int i = 0; i < n * m->ndof; i++) {
			int d = i % m->ndof;
			q[i] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
		}
	}
	double batch[BATCHES], sink = 0;
	for (int b = 0; b < BATCHES; b++) {
		double t0 = bench_now_us();
		for (int i = 0; i < n; i++) {
			memcpy(s->q, &q[(size_t)i * m->ndof], sizeof *q * (size_t)m->ndof);
			kin_update(m, s);
			sink += s->com[1];
		}
		batch[b] = (bench_now_us() - t0) / n;
	}
	qsort(batch, BATCHES, sizeof *batch, bench_cmp_double);
	printf("fk_human: %d segments, %d sites, %d dofs; %d postures x %d batches (checksum %.6g)\n",
	       m->nseg, m->nsite, m->ndof, n, BATCHES, sink);
	printf("BENCH fk.human.posture us=%.3f min_us=%.3f\n", batch[BATCHES / 2], batch[0]);
	free(q);
	state_free(s);
	model_free(m);
	return 0;
}
