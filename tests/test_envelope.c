/*
 * test_envelope.c - reach envelopes (assess/envelope.h) against independent
 * answers.
 *
 * Arms with limits against their analytic reachable sets: a ball shoulder
 * (turn about the vertical, tilt within alpha of it, twist about the upper
 * arm) and a hinged elbow (and, for three links, a hinged wrist). At a
 * distance rho from the shoulder the links deviate from the upper arm by
 * beta (the triangle of the links, by the law of cosines); turn and twist
 * sweep every azimuth, so the reachable directions at rho are those at an
 * angle from the vertical in [max(0, beta_min - alpha), beta_max + alpha].
 * The volume is the integral over rho of 2 pi (cos lo - cos hi) rho^2, and
 * membership is that test: the mesh's vertices lie in the set (within the
 * solver's millimetre), points two grid steps out along the normal do not,
 * and the volume agrees within what a surface at the grid's resolution
 * can miss.
 *
 * The human: the envelope's vertices are reached by "can reach" (residual
 * within 1 mm, every joint within its limits), points two steps out along
 * the normal are not; the volume converges as the grid halves; the body's
 * envelope holds the arm's; the comfort zone lies within the reach.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/envelope.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "pose/reach.h"

#define PI 3.14159265358979323846
static const double QID[4] = { 0, 0, 0, 1 };

/* ---- the analytic arms ---------------------------------------------------------- */

#define NBIN 2400
struct arm {
	int nlink;
	double len[3];
	double alpha;   /* the shoulder's tilt limit */
	double bend[2]; /* the elbow's and the wrist's upper limits (lower 0) */
	/* per bin of rho (RHO_BIN wide): the deviations beta reached there, -1 none */
	double bmin[NBIN], bmax[NBIN];
};
#define RHO_BIN 0.0005

/* the tip's distance and deviation from the upper arm at elbow angle t1, wrist t2 */
static void
arm_tip(const struct arm *a, double t1, double t2, double *rho, double *beta)
{
	double x = a->len[1] * sin(t1), y = a->len[0] + a->len[1] * cos(t1);
	if (a->nlink == 3) {
		x += a->len[2] * sin(t1 + t2);
		y += a->len[2] * cos(t1 + t2);
	}
	*rho = hypot(x, y);
	*beta = fabs(atan2(x, y));
}

/* the deviations reached at each distance: the two-link arm's one per distance, the
 * three-link arm's sampled every 0.1 degrees of both hinges */
static void
arm_tabulate(struct arm *a)
{
	for (int i = 0; i < NBIN; i++)
		a->bmin[i] = a->bmax[i] = -1;
	int n1 = (int)(a->bend[0] / (0.05 * PI / 180)) + 1;
	int n2 = a->nlink == 3 ? (int)(a->bend[1] / (0.1 * PI / 180)) + 1 : 1;
	for (int i = 0; i < n1; i++)
		for (int j = 0; j < n2; j++) {
			double rho, beta;
			arm_tip(a, a->bend[0] * i / (n1 - 1), n2 > 1 ? a->bend[1] * j / (n2 - 1) : 0,
				&rho, &beta);
			int b = (int)(rho / RHO_BIN);
			if (b >= NBIN)
				continue;
			if (a->bmin[b] < 0 || beta < a->bmin[b])
				a->bmin[b] = beta;
			if (beta > a->bmax[b])
				a->bmax[b] = beta;
		}
}

/* the angles from the vertical reachable in bin b: [lo, hi], or 0 when none */
static int
arm_band(const struct arm *a, int b, double *lo, double *hi)
{
	if (b < 0 || b >= NBIN || a->bmax[b] < 0)
		return 0;
	*lo = fmax(0, a->bmin[b] - a->alpha);
	*hi = fmin(PI, a->bmax[b] + a->alpha);
	return 1;
}

/* 1 when p (shoulder frame) is within tol of the reachable set (bins and angles widened) */
static int
arm_member(const struct arm *a, const double p[3], double tol)
{
	double rho = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
	double gamma = acos(fmax(-1, fmin(1, p[1] / rho)));
	int b0 = (int)((rho - tol) / RHO_BIN), b1 = (int)((rho + tol) / RHO_BIN);
	for (int b = b0; b <= b1; b++) {
		double lo, hi;
		if (arm_band(a, b, &lo, &hi) && gamma >= lo - tol / rho && gamma <= hi + tol / rho)
			return 1;
	}
	return 0;
}

static double
arm_volume(const struct arm *a)
{
	double v = 0;
	for (int b = 0; b < NBIN; b++) {
		double lo, hi, rho = (b + 0.5) * RHO_BIN;
		if (arm_band(a, b, &lo, &hi))
			v += 2 * PI * (cos(lo) - cos(hi)) * rho * rho * RHO_BIN;
	}
	return v;
}

/* the figure: base, upper arm, forearm (and hand), the links along +y from the shoulder at
 * the origin; joints "shoulder" (turn about y, tilt about z in [0, alpha], twist about y),
 * "elbow" and "wrist" (about z, [0, bend]) */
static struct model *
arm_model(const struct arm *a)
{
	struct model_builder *b = model_builder_create("arm");
	struct segment_def sd = segment_default_def();
	static const char *const names[4] = { "base", "upper", "fore", "hand" };
	int seg[4];
	for (int i = 0; i <= a->nlink; i++) {
		sd.name = names[i];
		sd.mass = 1;
		seg[i] = model_builder_segment(b, &sd);
	}
	double o[3] = { 0, 0, 0 };
	int root = model_builder_site(b, seg[0], "origin", o, QID), prev = root;
	struct joint_def jd = joint_default_def();
	static const char *const jn[3] = { "shoulder", "elbow", "wrist" };
	for (int i = 0; i < a->nlink; i++) {
		double end[3] = { 0, a->len[i], 0 };
		int in = model_builder_site(b, seg[i + 1], "proximal", o, QID);
		int out = model_builder_site(b, seg[i + 1], i + 1 == a->nlink ? "tip" : "distal", end,
					     QID);
		jd.name = jn[i];
		jd.site_from = prev;
		jd.site_to = in;
		if (i == 0) {
			/* started tilted and twisted: off the turn's singular vertical */
			jd.ndof = 3;
			jd.dof[0] = (struct dof_def){ DOF_ROTATION, 1, 1, -PI, PI, 0.3 };
			jd.dof[1] = (struct dof_def){ DOF_ROTATION, 2, 1, 0, a->alpha, a->alpha / 2 };
			jd.dof[2] = (struct dof_def){ DOF_ROTATION, 1, 1, -PI, PI, 0.2 };
		} else {
			jd.ndof = 1;
			jd.dof[0] = (struct dof_def){ DOF_ROTATION, 2, 1, 0, a->bend[i - 1],
						      a->bend[i - 1] / 2 };
		}
		assert_true(model_builder_joint(b, &jd) >= 0);
		prev = out;
	}
	model_builder_root(b, root, o, QID);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

static void
check_arm(struct arm *a, double res)
{
	arm_tabulate(a);
	struct model *m = arm_model(a);
	struct state *s = state_make(m);
	kin_update(m, s);
	char site[32];
	snprintf(site, sizeof site, "%s.tip", a->nlink == 3 ? "hand" : "fore");
	int tip = model_find_site(m, site);
	assert_true(tip >= 0);
	struct envelope_request req = { .resolution = res };
	struct envelope_mesh mesh;
	long solves = 0;
	char err[200];
	assert_int_equal(envelope_compute_chain(m, s, tip, -1, &req, &mesh, &solves, err, sizeof err),
			 0);
	assert_true(mesh.ntri > 0 && solves > 0);

	/* every vertex in the set; two steps out along the normal, out of it */
	int out_in = 0;
	double area = 0;
	for (int v = 0; v < mesh.nvert; v++) {
		double p[3], q[3];
		for (int i = 0; i < 3; i++) {
			p[i] = mesh.vert[3 * v + i];
			q[i] = p[i] + 2 * res * mesh.normal[3 * v + i];
		}
		if (!arm_member(a, p, 1.5e-3))
			fail_msg("vertex %d (%g %g %g) is not reachable", v, p[0], p[1], p[2]);
		out_in += arm_member(a, q, 0);
	}
	for (int t = 0; t < mesh.ntri; t++) {
		const int *tv = &mesh.tri[3 * t];
		double e1[3], e2[3];
		for (int i = 0; i < 3; i++) {
			e1[i] = mesh.vert[3 * tv[1] + i] - mesh.vert[3 * tv[0] + i];
			e2[i] = mesh.vert[3 * tv[2] + i] - mesh.vert[3 * tv[0] + i];
		}
		area += 0.5 * sqrt(pow(e1[1] * e2[2] - e1[2] * e2[1], 2) +
				   pow(e1[2] * e2[0] - e1[0] * e2[2], 2) +
				   pow(e1[0] * e2[1] - e1[1] * e2[0], 2));
	}
	/* a normal on a rim can point along the surface: allow one vertex in 200 */
	if (out_in * 200 > mesh.nvert)
		fail_msg("%d of %d points two steps outside are reachable", out_in, mesh.nvert);
	/* the vertices are on the boundary, the faces chords of it: the volume is short of
	 * the set's by at most the rims' and creases' cut, under half a step over the area */
	double exact = arm_volume(a);
	print_message("arm of %d links at %g m: volume %.5f, analytic %.5f, area %.3f, %ld solves\n",
		      a->nlink, res, mesh.volume, exact, area, solves);
	assert_true(mesh.volume <= exact * 1.01);
	assert_true(mesh.volume >= exact - 0.5 * res * area);
	/* the extent: the set reaches len sum along the vertical */
	double top = a->len[0] + a->len[1] + (a->nlink == 3 ? a->len[2] : 0);
	assert_true(fabs(mesh.hi[1] - top) < res);
	free(mesh.vert);
	free(mesh.normal);
	free(mesh.tri);
	state_free(s);
	model_free(m);
}

static void
test_two_link_arm_against_its_analytic_set(void **unused)
{
	(void)unused;
	struct arm a = { .nlink = 2, .len = { 0.30, 0.25 }, .alpha = 60 * PI / 180,
			 .bend = { 120 * PI / 180 } };
	check_arm(&a, 0.04);
}

static void
test_three_link_arm_against_its_analytic_set(void **unused)
{
	(void)unused;
	struct arm a = { .nlink = 3, .len = { 0.30, 0.20, 0.10 }, .alpha = 45 * PI / 180,
			 .bend = { 110 * PI / 180, 90 * PI / 180 } };
	check_arm(&a, 0.04);
}

/* ---- the human ---------------------------------------------------------------------- */

struct rig {
	struct model *m;
	struct state *s;
};

static void
rig_make(struct rig *g)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	g->m = human_build(&hd, err, sizeof err);
	assert_non_null(g->m);
	g->s = state_make(g->m);
	kin_update(g->m, g->s);
}

static void
rig_free(struct rig *g)
{
	state_free(g->s);
	model_free(g->m);
}

static void
envelope_of(const struct rig *g, enum reach_mode mode, double res, int comfort,
	    struct envelope *e)
{
	struct envelope_request req = { .side = BEHAVE_RIGHT, .mode = mode, .balance = 1,
					.resolution = res, .comfort = comfort };
	envelope_comfort_default(&req.comfort_ranges);
	char err[200];
	if (envelope_compute(g->m, g->s, NULL, NULL, 0, &req, e, err, sizeof err) < 0)
		fail_msg("envelope: %s", err);
	assert_true(e->reach.ntri > 0);
}

static unsigned
next_rand(unsigned *x)
{
	*x = *x * 1103515245u + 12345u;
	return *x >> 8;
}

/* random vertices of mesh are reached by "can reach" within its limits (those of model
 * lm); two steps out along the normal they are not */
static void
check_vertices(const struct rig *g, const struct model *lm, const struct envelope_mesh *mesh,
	       enum reach_mode mode, double res, int samples)
{
	struct reach *r = reach_make(lm);
	assert_non_null(r);
	unsigned seed = 12345;
	int far_reached = 0;
	for (int k = 0; k < samples; k++) {
		int v = (int)(next_rand(&seed) % (unsigned)mesh->nvert);
		struct reach_request q = { .side = BEHAVE_RIGHT, .mode = mode, .balance = 1,
					   .restarts = ENVELOPE_ARM_RESTARTS };
		for (int i = 0; i < 3; i++)
			q.target[i] = mesh->vert[3 * v + i];
		struct reach_result res_in, res_out;
		assert_int_equal(reach_solve(r, lm, g->s, NULL, NULL, 0, &q, &res_in), 0);
		if (res_in.distance > REACH_TOL_POS)
			fail_msg("vertex %d (%g %g %g): the palm stops %.4f m short", v, q.target[0],
				 q.target[1], q.target[2], res_in.distance);
		const struct state *ps = reach_posture(r);
		for (int d = 0; d < lm->ndof; d++)
			assert_true(ps->q[d] >= lm->dof_lo[d] - 1e-9 && ps->q[d] <= lm->dof_hi[d] + 1e-9);
		for (int i = 0; i < 3; i++)
			q.target[i] += 2 * res * mesh->normal[3 * v + i];
		assert_int_equal(reach_solve(r, lm, g->s, NULL, NULL, 0, &q, &res_out), 0);
		far_reached += res_out.reached;
	}
	if (far_reached)
		fail_msg("%d of %d points two steps outside were reached", far_reached, samples);
	reach_free(r);
}

static void
test_arm_envelope_converges_its_vertices_reached_and_outside_not(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g);
	double vol[3], res[3] = { 0.24, 0.12, 0.06 };
	struct envelope e;
	for (int i = 0; i < 3; i++) {
		envelope_of(&g, REACH_ARM, res[i], 0, &e);
		vol[i] = e.reach.volume;
		print_message("arm envelope at %g m: %.4f m^3, %d vertices, %ld solves\n", res[i],
			      vol[i], e.reach.nvert, e.solves);
		if (i < 2)
			envelope_free(&e);
	}
	/* the volume converges as the grid halves */
	assert_true(fabs(vol[2] - vol[1]) < fabs(vol[1] - vol[0]));
	assert_true(fabs(vol[2] - vol[1]) < 0.05 * vol[2]);
	check_vertices(&g, g.m, &e.reach, REACH_ARM, 0.06, 40);
	/* the palm's current place is inside; a point 2 m overhead is not */
	int palm = model_find_site(g.m, "hand_r.palm");
	assert_true(palm >= 0);
	double over[3] = { 0, 3.5, 0 };
	assert_int_equal(envelope_mesh_contains(&e.reach, g.s->site_xf[palm].p), 1);
	assert_int_equal(envelope_mesh_contains(&e.reach, over), 0);
	assert_true(e.solves > 0 && e.seconds > 0);
	envelope_free(&e);
	rig_free(&g);
}

static void
test_body_envelope_holds_the_arm_one(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g);
	struct envelope arm, body;
	envelope_of(&g, REACH_ARM, 0.25, 0, &arm);
	envelope_of(&g, REACH_BODY, 0.25, 0, &body);
	/* where the two sets share their boundary (overhead, where standing straight is
	 * already the highest) the two grids' chords cross: within a step of it */
	int outside = 0, near = 0;
	for (int v = 0; v < arm.reach.nvert; v++) {
		double p[3], in[3];
		for (int i = 0; i < 3; i++) {
			p[i] = arm.reach.vert[3 * v + i];
			in[i] = p[i] - 0.25 * arm.reach.normal[3 * v + i];
		}
		if (envelope_mesh_contains(&body.reach, p))
			continue;
		near++;
		outside += !envelope_mesh_contains(&body.reach, in);
	}
	print_message("body %.3f m^3, arm %.3f m^3; %d of %d arm vertices within a step outside "
		      "the body's, %d further\n",
		      body.reach.volume, arm.reach.volume, near, arm.reach.nvert, outside);
	assert_int_equal(outside, 0);
	assert_true(body.reach.volume > arm.reach.volume);
	envelope_free(&arm);
	envelope_free(&body);
	rig_free(&g);
}

static void
test_comfort_zone_within_the_reach_and_reached_within_its_ranges(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g);
	struct envelope e;
	envelope_of(&g, REACH_ARM, 0.06, 1, &e);
	assert_true(e.comfort.ntri > 0);
	assert_true(e.comfort.volume > 0 && e.comfort.volume < e.reach.volume);
	int outside = 0;
	for (int v = 0; v < e.comfort.nvert; v++) {
		double p[3];
		for (int i = 0; i < 3; i++)
			p[i] = e.comfort.vert[3 * v + i];
		outside += !envelope_mesh_contains(&e.reach, p);
	}
	assert_int_equal(outside, 0);
	/* the comfort zone's vertices reached with the comfort ranges as the limits */
	struct model *cm = model_copy(g.m);
	assert_non_null(cm);
	char err[200];
	struct envelope_comfort c;
	envelope_comfort_default(&c);
	assert_int_equal(envelope_comfort_apply(&c, cm, BEHAVE_RIGHT, err, sizeof err), 0);
	int elbow = model_find_joint(cm, "elbow_r");
	assert_true(elbow >= 0);
	assert_true(fabs(cm->dof_lo[cm->jnt_dof0[elbow]] - 60 * PI / 180) < 1e-12);
	check_vertices(&g, cm, &e.comfort, REACH_ARM, 0.06, 30);
	model_free(cm);
	envelope_free(&e);
	rig_free(&g);
}

static void
test_comfort_defaults_cited_and_parsed(void **unused)
{
	(void)unused;
	struct envelope_comfort c;
	envelope_comfort_default(&c);
	assert_true(c.n > 0);
	for (int i = 0; i < c.n; i++) {
		assert_non_null(envelope_comfort_source(i));
		assert_true(c.r[i].lo <= c.r[i].hi);
	}
	assert_null(envelope_comfort_source(c.n));
	char err[200];
	int n = c.n;
	assert_int_equal(envelope_comfort_parse("elbow.0=50,110; knee.0 = 0 , 30", &c, err,
						sizeof err),
			 0);
	assert_int_equal(c.n, n + 1);
	int found = 0;
	for (int i = 0; i < c.n; i++)
		if (!strcmp(c.r[i].joint, "elbow") && c.r[i].dof == 0) {
			assert_true(c.r[i].lo == 50 && c.r[i].hi == 110);
			found = 1;
		}
	assert_true(found);
	struct envelope_comfort before = c;
	static const char *const bad[] = { "elbow", "elbow.0=1", "elbow.x=1,2", "elbow.0=20,10",
					   "elbow.0=1,2,", ".0=1,2", "elbow.0=1,2;;" , "elbow.0=nan,1" };
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		err[0] = 0;
		assert_int_equal(envelope_comfort_parse(bad[i], &c, err, sizeof err), -1);
		assert_true(err[0] != 0);
		assert_memory_equal(&c, &before, sizeof c);
	}
	/* ranges the joint cannot take, or joints the figure lacks, are refused */
	struct rig g;
	rig_make(&g);
	struct model *cm = model_copy(g.m);
	struct envelope_comfort x = { 0 };
	assert_int_equal(envelope_comfort_parse("elbow.0=-40,-20", &x, err, sizeof err), 0);
	assert_int_equal(envelope_comfort_apply(&x, cm, BEHAVE_RIGHT, err, sizeof err), -1);
	x.n = 0;
	assert_int_equal(envelope_comfort_parse("tail.0=0,10", &x, err, sizeof err), 0);
	assert_int_equal(envelope_comfort_apply(&x, cm, BEHAVE_RIGHT, err, sizeof err), -1);
	model_free(cm);
	rig_free(&g);
}

static void
test_bad_requests_are_refused(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g);
	struct envelope e;
	char err[200];
	struct envelope_request ok = { .side = BEHAVE_RIGHT, .mode = REACH_ARM, .resolution = 0.2 };
	struct envelope_request bad[4] = { ok, ok, ok, ok };
	bad[0].side = 7;
	bad[1].mode = 9;
	bad[2].resolution = 0.001;
	bad[3].resolution = NAN;
	for (int i = 0; i < 4; i++) {
		err[0] = 0;
		assert_int_equal(envelope_compute(g.m, g.s, NULL, NULL, 0, &bad[i], &e, err, sizeof err),
				 -1);
		assert_true(err[0] != 0);
		assert_int_equal(e.reach.nvert, 0);
	}
	rig_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_link_arm_against_its_analytic_set),
		cmocka_unit_test(test_three_link_arm_against_its_analytic_set),
		cmocka_unit_test(test_arm_envelope_converges_its_vertices_reached_and_outside_not),
		cmocka_unit_test(test_body_envelope_holds_the_arm_one),
		cmocka_unit_test(test_comfort_zone_within_the_reach_and_reached_within_its_ranges),
		cmocka_unit_test(test_comfort_defaults_cited_and_parsed),
		cmocka_unit_test(test_bad_requests_are_refused),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
