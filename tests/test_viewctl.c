/*
 * test_viewctl.c - viewing control against Appendix C: every camera
 * operation against its equation of C.2, evaluated here as the
 * dissertation writes it (4 x 4 matrices acting on row vectors, position
 * in the bottom row: T = C R^-1, C' = T D R for the sweep, the pivot at
 * the camera's origin for the pan, C'p = Cp + theta Cz for the zoom) on
 * random cameras; the buttons and CONTROL; V, ESC and C; the snap's eased
 * in-betweens under a virtual clock at 10 to 120 frames a second; and
 * 10 000 random operations that never twist the camera nor pass the poles.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <math.h>
#include <string.h>

#include "draw/view.h"
#include "interact/viewctl.h"
#include "interact/viewop.h"

#include "test_random.h"
#include "test_util.h"

#define DEG (M_PI / 180)

/* ---- the dissertation's matrices: row vectors, position in the bottom row ------ */

typedef double m4[4][4];

static void
m4_mul(m4 a, m4 b, m4 dest)
{
	for (int i = 0; i < 4; i++)
		for (int j = 0; j < 4; j++) {
			dest[i][j] = 0;
			for (int k = 0; k < 4; k++)
				dest[i][j] += a[i][k] * b[k][j];
		}
}

static void
m4_translation(const double v[3], m4 dest)
{
	memset(dest, 0, sizeof(m4));
	for (int i = 0; i < 4; i++)
		dest[i][i] = 1;
	for (int j = 0; j < 3; j++)
		dest[3][j] = v[j];
}

/* a right-hand turn by angle about unit axis a (Rodrigues), as a row-vector matrix */
static void
m4_rotation(const double a[3], double angle, m4 dest)
{
	double c = cos(angle), s = sin(angle), col[3][3];
	const double k[3][3] = { { 0, -a[2], a[1] }, { a[2], 0, -a[0] }, { -a[1], a[0], 0 } };
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			col[i][j] = (i == j) * c + s * k[i][j] + (1 - c) * a[i] * a[j];
	memset(dest, 0, sizeof(m4));
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			dest[i][j] = col[j][i]; /* row vectors: the transpose */
	dest[3][3] = 1;
}

/* the camera's global transform C: its axes are the rows, its origin the bottom row */
static void
m4_of_camera(const struct camera *c, m4 dest)
{
	memset(dest, 0, sizeof(m4));
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++)
			dest[i][j] = c->xf.r[3 * j + i];
		dest[3][i] = c->xf.p[i];
	}
	dest[3][3] = 1;
}

static void
axis(const struct camera *c, int k, double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = c->xf.r[3 * i + k];
}

/* the view reference point: vrd along -z from the camera's origin (C.1.3) */
static void
vrp(const struct camera *c, double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = c->xf.p[i] - c->vrd * c->xf.r[3 * i + 2];
}

/* the angle of the camera's z axis above the horizontal */
static double
elevation(const struct camera *c)
{
	return asin(fmax(-1, fmin(1, c->xf.r[5])));
}

static void
assert_camera_is(const struct camera *c, m4 want, double tol)
{
	m4 got;
	m4_of_camera(c, got);
	for (int i = 0; i < 4; i++)
		for (int j = 0; j < 4; j++)
			assert_near(got[i][j], want[i][j], tol);
}

static void
assert_vec_near(const double a[3], const double b[3], double tol)
{
	for (int i = 0; i < 3; i++)
		assert_near(a[i], b[i], tol);
}

/* a camera somewhere in a room, aimed at a point 0.5 to 6 m away, elevation within +-elev_max */
static struct camera
random_camera(double elev_max)
{
	struct camera c;
	view_camera_default(&c);
	double eye[3] = { span(-5, 5), span(0.2, 3), span(-5, 5) };
	double yaw = span(-M_PI, M_PI), pitch = span(-elev_max, elev_max), d = span(0.5, 6);
	double target[3] = { eye[0] + d * cos(pitch) * sin(yaw), eye[1] + d * sin(pitch),
			     eye[2] + d * cos(pitch) * cos(yaw) };
	assert_int_equal(view_camera_aim(&c, eye, target), 0);
	return c;
}

/* ---- the equations of C.2 ----------------------------------------------------- */

/* C' = T D P with T = C P^-1: the camera turned by theta about d_axis through the pivot */
static void
turn_about_pivot_by_equation(const struct camera *c, const double pivot[3], const double d_axis[3],
			     double theta, m4 dest)
{
	double minus_pivot[3];
	for (int i = 0; i < 3; i++)
		minus_pivot[i] = -pivot[i];
	m4 C, P, P_inv, T, D, TD;
	m4_of_camera(c, C);
	m4_translation(pivot, P);
	m4_translation(minus_pivot, P_inv);
	m4_mul(C, P_inv, T);
	m4_rotation(d_axis, theta, D);
	m4_mul(T, D, TD);
	m4_mul(TD, P, dest);
}

/* C.2.1.2: the pivot R is the view reference point, aligned with the world */
static void
sweep_by_equation(const struct camera *c, const double d_axis[3], double theta, m4 dest)
{
	double r[3];
	vrp(c, r);
	turn_about_pivot_by_equation(c, r, d_axis, theta, dest);
}

/* C.2.2.2: the same with the pivot at the camera's own origin */
static void
pan_by_equation(const struct camera *c, const double d_axis[3], double theta, m4 dest)
{
	turn_about_pivot_by_equation(c, c->xf.p, d_axis, theta, dest);
}

/* C.2.2.2's other reading: the turn about the camera's own local_axis, applied locally (D C) */
static void
pan_locally(const struct camera *c, const double local_axis[3], double theta, m4 dest)
{
	m4 C, D;
	m4_of_camera(c, C);
	m4_rotation(local_axis, theta, D);
	m4_mul(D, C, dest);
}

static const double WORLD_Y[3] = { 0, 1, 0 };

static void
test_sweep_horizontal_is_TDR_about_the_vertical(void **state)
{
	(void)state;
	rng_state = 1;
	for (int n = 0; n < 500; n++) {
		struct camera c = random_camera(80 * DEG);
		double theta = span(-M_PI, M_PI), r0[3], r1[3];
		m4 want;
		sweep_by_equation(&c, WORLD_Y, theta, want);
		vrp(&c, r0);
		double vrd = c.vrd, elev = elevation(&c);
		assert_near(viewop_sweep_horizontal(&c, theta), theta, 0);
		assert_camera_is(&c, want, 1e-12);
		/* the camera keeps its elevation, distance and reference point */
		vrp(&c, r1);
		assert_vec_near(r1, r0, 1e-12);
		assert_near(c.vrd, vrd, 0);
		assert_near(elevation(&c), elev, 1e-12);
	}
}

static void
test_sweep_vertical_is_TDR_about_the_camera_x(void **state)
{
	(void)state;
	rng_state = 2;
	for (int n = 0; n < 500; n++) {
		struct camera c = random_camera(60 * DEG);
		double theta = span(-25 * DEG, 25 * DEG), cx[3], r0[3], r1[3];
		axis(&c, 0, cx);
		m4 want;
		sweep_by_equation(&c, cx, theta, want);
		vrp(&c, r0);
		double elev = elevation(&c);
		assert_near(viewop_sweep_vertical(&c, theta), theta, 1e-12);
		assert_camera_is(&c, want, 1e-12);
		vrp(&c, r1);
		assert_vec_near(r1, r0, 1e-12);
		/* a right-hand turn about x lowers z: the camera sinks for positive theta */
		assert_near(elevation(&c), elev - theta, 1e-12);
	}
}

static void
test_sweep_vertical_stops_short_of_the_poles(void **state)
{
	(void)state;
	rng_state = 3;
	for (int n = 0; n < 200; n++) {
		struct camera c = random_camera(80 * DEG);
		double elev = elevation(&c), r0[3], r1[3], cx[3];
		int up = n % 2;
		/* ask for 10 degrees past a pole */
		double asked = up ? elev - 100 * DEG : elev + 100 * DEG;
		double limit = up ? 89 * DEG : -89 * DEG;
		axis(&c, 0, cx);
		vrp(&c, r0);
		m4 want;
		sweep_by_equation(&c, cx, elev - limit, want);
		double turned = viewop_sweep_vertical(&c, asked);
		assert_near(turned, elev - limit, 1e-12);
		assert_near(elevation(&c), limit, 1e-12);
		assert_camera_is(&c, want, 1e-12);
		vrp(&c, r1);
		assert_vec_near(r1, r0, 1e-12);
		/* further that way: nothing */
		assert_near(viewop_sweep_vertical(&c, up ? -DEG : DEG), 0, 1e-12);
		assert_near(viewop_pan_vertical(&c, up ? -DEG : DEG), 0, 1e-12);
	}
}

static void
test_pan_horizontal_is_RD_about_the_vertical(void **state)
{
	(void)state;
	rng_state = 4;
	for (int n = 0; n < 500; n++) {
		struct camera c = random_camera(80 * DEG);
		double theta = span(-M_PI, M_PI), p0[3];
		m4 want, local;
		pan_by_equation(&c, WORLD_Y, theta, want);
		/* R_y mapped to the camera's frame */
		double y_local[3] = { c.xf.r[3], c.xf.r[4], c.xf.r[5] };
		pan_locally(&c, y_local, theta, local);
		memcpy(p0, c.xf.p, sizeof p0);
		double vrd = c.vrd, elev = elevation(&c);
		assert_near(viewop_pan_horizontal(&c, theta), theta, 0);
		assert_camera_is(&c, want, 1e-12);
		assert_camera_is(&c, local, 1e-12);
		/* the camera stays; its reference point circles it at the same distance */
		assert_memory_equal(c.xf.p, p0, sizeof p0);
		assert_near(c.vrd, vrd, 0);
		assert_near(elevation(&c), elev, 1e-12);
	}
}

static void
test_pan_vertical_is_RD_about_the_camera_x(void **state)
{
	(void)state;
	rng_state = 5;
	const double local_x[3] = { 1, 0, 0 };
	for (int n = 0; n < 500; n++) {
		struct camera c = random_camera(60 * DEG);
		double theta = span(-25 * DEG, 25 * DEG), cx[3], p0[3];
		axis(&c, 0, cx);
		m4 want, local;
		pan_by_equation(&c, cx, theta, want);
		pan_locally(&c, local_x, theta, local);
		memcpy(p0, c.xf.p, sizeof p0);
		double elev = elevation(&c);
		assert_near(viewop_pan_vertical(&c, theta), theta, 1e-12);
		assert_camera_is(&c, want, 1e-12);
		assert_camera_is(&c, local, 1e-12);
		assert_memory_equal(c.xf.p, p0, sizeof p0);
		/* the line of sight (-z) rises by theta */
		assert_near(elevation(&c), elev - theta, 1e-12);
	}
}

/* C.2.3.2: C'p = Cp + theta Cz, the orientation unchanged, R kept */
static void
test_zoom_moves_along_z_keeping_the_reference_point(void **state)
{
	(void)state;
	rng_state = 6;
	for (int n = 0; n < 500; n++) {
		struct camera c = random_camera(80 * DEG);
		double theta = span(-0.9 * c.vrd, 3), want[3], r0[3], r1[3], z[3];
		axis(&c, 2, z);
		for (int i = 0; i < 3; i++)
			want[i] = c.xf.p[i] + theta * z[i];
		vrp(&c, r0);
		double rot0[9], vrd = c.vrd;
		memcpy(rot0, c.xf.r, sizeof rot0);
		assert_near(viewop_zoom(&c, theta), theta, 1e-12);
		assert_vec_near(c.xf.p, want, 1e-12);
		assert_memory_equal(c.xf.r, rot0, sizeof rot0);
		assert_near(c.vrd, vrd + theta, 1e-12);
		vrp(&c, r1);
		assert_vec_near(r1, r0, 1e-12);
	}
	/* never onto or past the reference point */
	struct camera c = random_camera(80 * DEG);
	double vrd = c.vrd;
	assert_near(viewop_zoom(&c, -2 * vrd), VIEWOP_VRD_MIN - vrd, 1e-12);
	assert_near(c.vrd, VIEWOP_VRD_MIN, 0);
	assert_near(viewop_zoom(&c, -1), 0, 0);
	assert_near(viewop_zoom(&c, NAN), 0, 0);
	assert_true(c.vrd > 0);
}

/* ---- the change view mode ----------------------------------------------------- */

static struct input_event_rec
ev_of(enum input_kind kind, unsigned code, int value, double x, double y)
{
	struct input_event_rec e = { .kind = (uint8_t)kind, .code = (uint16_t)code,
				     .value = value, .x = x, .y = y };
	return e;
}

static enum viewctl_result
feed(struct viewctl *vc, struct camera *c, enum input_kind kind, unsigned code, int value)
{
	struct input_event_rec e = ev_of(kind, code, value, 0, 0);
	return viewctl_event(vc, c, 0, &e);
}

static enum viewctl_result
motion(struct viewctl *vc, struct camera *c, double dx, double dy)
{
	struct input_event_rec e = ev_of(INPUT_MOTION, 0, 0, dx, dy);
	return viewctl_event(vc, c, 0, &e);
}

static void
enter(struct viewctl *vc, struct camera *c, int caller_mode)
{
	struct input_event_rec v = ev_of(INPUT_KEY, KEY_V, 1, 0, 0);
	assert_int_equal(viewctl_event(vc, c, caller_mode, &v), VIEWCTL_ENTERED);
	assert_int_equal(vc->state, VIEWCTL_VIEWING);
	feed(vc, c, INPUT_KEY, KEY_V, 0);
}

static void
assert_same_camera(const struct camera *a, const struct camera *b)
{
	assert_memory_equal(a, b, sizeof *a);
}

/* which operation each button combination and CONTROL selects, with which motion and sign */
static void
test_buttons_and_control_select_the_operation(void **state)
{
	(void)state;
	rng_state = 7;
	struct viewctl_gains g = viewctl_default_gains();
	g.rad_per_px = 0.3 * DEG;
	g.m_per_px = 0.02;
	const double dx = 12, dy = -7, a = g.rad_per_px, m = g.m_per_px;
	const unsigned codes[3] = { BTN_LEFT, BTN_MIDDLE, BTN_RIGHT };
	for (unsigned held = 0; held < 8; held++) {
		for (int control = 0; control < 2; control++) {
			struct camera c = random_camera(45 * DEG), want = c;
			struct viewctl vc;
			viewctl_init(&vc, &g);
			enter(&vc, &c, 0);
			if (control)
				feed(&vc, &c, INPUT_KEY, KEY_LEFTCTRL, 1);
			for (int b = 0; b < 3; b++)
				if (held & (1u << b))
					assert_int_equal(feed(&vc, &c, INPUT_BUTTON, codes[b], 1),
							 VIEWCTL_TAKEN);
			enum viewctl_result r = motion(&vc, &c, dx, dy);
			/* what viewctl.h promises, composed by hand */
			int L = held & 1, M = (held >> 1) & 1, R = (held >> 2) & 1;
			int acts = held != 0 && held != 7;
			if (acts && L) {
				if (control)
					viewop_pan_horizontal(&want, -a * dx);
				else
					viewop_sweep_horizontal(&want, a * dx);
			}
			if (acts && M) {
				if (control)
					viewop_pan_vertical(&want, -a * dy);
				else
					viewop_sweep_vertical(&want, a * dy);
			}
			if (acts && R)
				viewop_zoom(&want, m * (M && !L ? dx : dy));
			assert_int_equal(r, acts ? VIEWCTL_CHANGED : VIEWCTL_TAKEN);
			assert_same_camera(&c, &want);
		}
	}
}

/* whatever moves follows the pointer (C.1.2's eyeball in hand) */
static void
test_the_moving_part_follows_the_pointer(void **state)
{
	(void)state;
	rng_state = 8;
	struct viewctl_gains g = viewctl_default_gains();
	for (int n = 0; n < 50; n++) {
		struct camera c0 = random_camera(45 * DEG), c;
		double x0[3], z0[3], z1[3], r0[3], r1[3];
		axis(&c0, 0, x0);
		axis(&c0, 2, z0);
		vrp(&c0, r0);
		struct viewctl vc;

		/* left, pointer right: the camera goes right round R */
		c = c0;
		viewctl_init(&vc, &g);
		enter(&vc, &c, 0);
		feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1);
		motion(&vc, &c, 20, 0);
		double dp[3] = { c.xf.p[0] - c0.xf.p[0], c.xf.p[1] - c0.xf.p[1], c.xf.p[2] - c0.xf.p[2] };
		assert_true(dp[0] * x0[0] + dp[1] * x0[1] + dp[2] * x0[2] > 0);

		/* middle, pointer up: the camera rises */
		c = c0;
		viewctl_init(&vc, &g);
		enter(&vc, &c, 0);
		feed(&vc, &c, INPUT_BUTTON, BTN_MIDDLE, 1);
		motion(&vc, &c, 0, -20);
		assert_true(c.xf.p[1] > c0.xf.p[1]);

		/* right, pointer up: nearer R, which stays */
		c = c0;
		viewctl_init(&vc, &g);
		enter(&vc, &c, 0);
		feed(&vc, &c, INPUT_BUTTON, BTN_RIGHT, 1);
		motion(&vc, &c, 0, -20);
		assert_true(c.vrd < c0.vrd);
		vrp(&c, r1);
		assert_vec_near(r1, r0, 1e-12);

		/* CONTROL + left, pointer right: the line of sight turns right */
		c = c0;
		viewctl_init(&vc, &g);
		enter(&vc, &c, 0);
		feed(&vc, &c, INPUT_KEY, KEY_RIGHTCTRL, 1);
		feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1);
		motion(&vc, &c, 20, 0);
		axis(&c, 2, z1);
		assert_true(-(z1[0] * x0[0] + z1[1] * x0[1] + z1[2] * x0[2]) > 0);
		assert_memory_equal(c.xf.p, c0.xf.p, sizeof c.xf.p);

		/* CONTROL + middle, pointer up: the line of sight rises */
		c = c0;
		viewctl_init(&vc, &g);
		enter(&vc, &c, 0);
		feed(&vc, &c, INPUT_KEY, KEY_LEFTCTRL, 1);
		feed(&vc, &c, INPUT_BUTTON, BTN_MIDDLE, 1);
		motion(&vc, &c, 0, -20);
		axis(&c, 2, z1);
		assert_true(-z1[1] > -z0[1]);
	}
}

static void
test_v_enters_esc_keeps_c_restores(void **state)
{
	(void)state;
	rng_state = 9;
	struct viewctl_gains g = viewctl_default_gains();
	struct viewctl vc;
	viewctl_init(&vc, &g);
	struct camera c = random_camera(45 * DEG), first = c;

	/* idle: everything but V is the caller's */
	assert_int_equal(feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1), VIEWCTL_PASS);
	assert_int_equal(motion(&vc, &c, 30, 30), VIEWCTL_PASS);
	assert_int_equal(feed(&vc, &c, INPUT_KEY, KEY_ESC, 1), VIEWCTL_PASS);
	assert_same_camera(&c, &first);

	/* V in the middle of a manipulation (left held): that button does nothing here */
	enter(&vc, &c, 42);
	assert_int_equal(motion(&vc, &c, 30, 30), VIEWCTL_TAKEN);
	assert_same_camera(&c, &first);
	assert_int_equal(feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 0), VIEWCTL_TAKEN);
	feed(&vc, &c, INPUT_BUTTON, BTN_MIDDLE, 1);
	assert_int_equal(motion(&vc, &c, 5, -40), VIEWCTL_CHANGED);
	feed(&vc, &c, INPUT_BUTTON, BTN_MIDDLE, 0);
	/* V again changes nothing, nor what C goes back to */
	assert_int_equal(feed(&vc, &c, INPUT_KEY, KEY_V, 1), VIEWCTL_TAKEN);
	feed(&vc, &c, INPUT_BUTTON, BTN_RIGHT, 1);
	motion(&vc, &c, 0, 25);
	/* C: the camera exactly as at V, and the caller's mode back */
	assert_int_equal(feed(&vc, &c, INPUT_KEY, KEY_C, 1), VIEWCTL_ENDED);
	assert_same_camera(&c, &first);
	assert_int_equal(vc.caller_mode, 42);
	assert_int_equal(vc.state, VIEWCTL_IDLE);

	/* ESC keeps the view */
	enter(&vc, &c, 7);
	feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1);
	motion(&vc, &c, 33, 0);
	struct camera moved = c;
	assert_false(memcmp(&moved, &first, sizeof moved) == 0);
	assert_int_equal(feed(&vc, &c, INPUT_KEY, KEY_ESC, 1), VIEWCTL_ENDED);
	assert_same_camera(&c, &moved);
	assert_int_equal(vc.caller_mode, 7);
	assert_int_equal(vc.state, VIEWCTL_IDLE);
	/* and the button still down afterwards is the caller's again */
	assert_int_equal(motion(&vc, &c, 33, 0), VIEWCTL_PASS);
	assert_same_camera(&c, &moved);

	/* CONTROL pressed before V counts */
	feed(&vc, &c, INPUT_KEY, KEY_LEFTCTRL, 1);
	enter(&vc, &c, 1);
	feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1);
	motion(&vc, &c, 10, 0);
	assert_memory_equal(c.xf.p, moved.xf.p, sizeof c.xf.p);
}

/* several views: each machine moves its own camera only */
static void
test_each_view_its_own_camera(void **state)
{
	(void)state;
	rng_state = 10;
	struct viewctl_gains g = viewctl_default_gains(), g2 = g;
	g2.rad_per_px = 2 * g.rad_per_px;
	struct viewctl a, b;
	viewctl_init(&a, &g);
	viewctl_init(&b, &g2);
	struct camera ca = random_camera(45 * DEG), cb = random_camera(45 * DEG), cb0 = cb;
	struct camera want = ca;
	enter(&a, &ca, 3);
	feed(&a, &ca, INPUT_BUTTON, BTN_LEFT, 1);
	assert_int_equal(motion(&a, &ca, 10, 0), VIEWCTL_CHANGED);
	assert_int_equal(motion(&b, &cb, 10, 0), VIEWCTL_PASS);
	assert_same_camera(&cb, &cb0);
	viewop_sweep_horizontal(&want, 10 * g.rad_per_px);
	assert_same_camera(&ca, &want);
	/* b's gains are b's */
	enter(&b, &cb, 4);
	feed(&b, &cb, INPUT_BUTTON, BTN_LEFT, 1);
	motion(&b, &cb, 10, 0);
	want = cb0;
	viewop_sweep_horizontal(&want, 10 * g2.rad_per_px);
	assert_same_camera(&cb, &want);
}

/* ---- the snap ----------------------------------------------------------------- */

/* signed angle from horizontal direction a to b about world y */
static double
turn_about_y(const double a[3], const double b[3])
{
	return atan2(a[2] * b[0] - a[0] * b[2], a[0] * b[0] + a[2] * b[2]);
}

static double
ease_by_hand(double u)
{
	return 3 * u * u - 2 * u * u * u;
}

/* the direction of the line of sight (-z) */
static void
sight(const struct camera *c, double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = -c->xf.r[3 * i + 2];
}

static double
angle_between(const double a[3], const double b[3])
{
	double cr[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
			 a[0] * b[1] - a[1] * b[0] };
	return atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]),
		     a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

/* a target off to one side, at least 30 degrees round, within 60 degrees of the horizon */
static void
random_target(const struct camera *c, double dest[3])
{
	double s[3];
	sight(c, s);
	double yaw = atan2(s[0], s[2]) + (urand() < 0.5 ? -1 : 1) * span(30 * DEG, 170 * DEG);
	double pitch = span(-60 * DEG, 60 * DEG), d = span(0.5, 8);
	dest[0] = c->xf.p[0] + d * cos(pitch) * sin(yaw);
	dest[1] = c->xf.p[1] + d * sin(pitch);
	dest[2] = c->xf.p[2] + d * cos(pitch) * cos(yaw);
}

static void
start_snap(struct viewctl *vc, struct camera *c, const double target[3], uint64_t t0)
{
	enter(vc, c, 0);
	assert_int_equal(feed(vc, c, INPUT_KEY, KEY_S, 1), VIEWCTL_TAKEN);
	assert_int_equal(vc->state, VIEWCTL_SNAP_PICK);
	/* pointer motion while choosing moves nothing */
	struct camera before = *c;
	assert_int_equal(motion(vc, c, 40, 40), VIEWCTL_TAKEN);
	assert_same_camera(c, &before);
	assert_int_equal(feed(vc, c, INPUT_BUTTON, BTN_LEFT, 1), VIEWCTL_PICK);
	assert_int_equal(viewctl_snap_to(vc, c, target, t0), VIEWCTL_TAKEN);
	assert_int_equal(vc->state, VIEWCTL_SNAPPING);
}

static void
test_snap_finishes_within_a_second_at_any_frame_rate(void **state)
{
	(void)state;
	rng_state = 11;
	const int fps[4] = { 10, 30, 60, 120 };
	for (int f = 0; f < 4; f++) {
		uint64_t frame_us = 1000000 / (uint64_t)fps[f];
		for (int n = 0; n < 20; n++) {
			struct viewctl_gains g = viewctl_default_gains();
			struct viewctl vc;
			viewctl_init(&vc, &g);
			struct camera c = random_camera(60 * DEG), c0 = c;
			double target[3], to_target[3], s0[3], s[3];
			random_target(&c, target);
			for (int i = 0; i < 3; i++)
				to_target[i] = target[i] - c.xf.p[i];
			sight(&c0, s0);
			/* the two turns of C.3: about the vertical, then up or down */
			double dheading = turn_about_y(s0, to_target);
			double delev = asin(to_target[1] / sqrt(to_target[0] * to_target[0] +
								to_target[1] * to_target[1] +
								to_target[2] * to_target[2])) -
				       asin(s0[1]);
			uint64_t t0 = 5000000 + (uint64_t)n, t = t0;
			start_snap(&vc, &c, target, t0);
			double heading_done = 0, elev_done = 0;
			int frames = 0;
			while (vc.state == VIEWCTL_SNAPPING) {
				t += frame_us;
				frames++;
				assert_true(frames <= fps[f] + 1);
				assert_int_equal(viewctl_frame(&vc, &c, t), VIEWCTL_CHANGED);
				/* a pan: the camera stays and never twists */
				assert_memory_equal(c.xf.p, c0.xf.p, sizeof c.xf.p);
				assert_true(c.xf.r[3] == 0);
				/* both turns go one way, never back, never beyond */
				sight(&c, s);
				double h = turn_about_y(s0, s) / dheading, e = (asin(s[1]) - asin(s0[1])) / delev;
				assert_true(h >= heading_done - 1e-12 && h <= 1 + 1e-12);
				if (fabs(delev) > 1e-6)
					assert_true(e >= elev_done - 1e-12 && e <= 1 + 1e-12);
				heading_done = h;
				elev_done = e;
			}
			assert_int_equal(vc.state, VIEWCTL_VIEWING);
			assert_true(t - t0 <= 1000000 + frame_us);
			/* ends on the target */
			double r[3];
			vrp(&c, r);
			assert_vec_near(r, target, 1e-12);
			sight(&c, s);
			assert_near(angle_between(s, to_target), 0, 1e-12);
		}
	}
}

/* with no minimum step, heading and elevation follow 3u^2 - 2u^3 of their turns exactly */
static void
test_snap_in_betweens_are_eased(void **state)
{
	(void)state;
	rng_state = 12;
	for (int n = 0; n < 50; n++) {
		struct viewctl_gains g = viewctl_default_gains();
		g.snap_min_rad = 0;
		struct viewctl vc;
		viewctl_init(&vc, &g);
		struct camera c = random_camera(60 * DEG), c0 = c;
		double target[3], s0[3], s[3], tt[3];
		random_target(&c, target);
		sight(&c0, s0);
		for (int i = 0; i < 3; i++)
			tt[i] = target[i] - c.xf.p[i];
		double dheading = turn_about_y(s0, tt);
		double pitch0 = asin(s0[1]), pitch1 = asin(tt[1] / sqrt(tt[0] * tt[0] + tt[1] * tt[1] +
									 tt[2] * tt[2]));
		uint64_t t0 = 1000, frame_us = 16667, t = t0;
		start_snap(&vc, &c, target, t0);
		double last_step = 0, mid_step = 0, first_step = -1, prev_heading = 0;
		while (vc.state == VIEWCTL_SNAPPING) {
			t += frame_us;
			viewctl_frame(&vc, &c, t);
			double u = fmin(1, (double)(t - t0) / 1e6);
			sight(&c, s);
			double heading = turn_about_y(s0, s);
			assert_near(heading, ease_by_hand(u) * dheading, 1e-12);
			assert_near(asin(s[1]), pitch0 + ease_by_hand(u) * (pitch1 - pitch0), 1e-12);
			double step = fabs(heading - prev_heading);
			if (first_step < 0)
				first_step = step;
			if (fabs(u - 0.5) < 0.01)
				mid_step = step;
			last_step = step;
			prev_heading = heading;
		}
		/* slow in, slow out */
		assert_true(first_step < 0.05 * mid_step);
		assert_true(last_step < 0.05 * mid_step);
	}
}

static void
test_snap_turns_at_least_the_minimum_per_frame(void **state)
{
	(void)state;
	rng_state = 13;
	struct viewctl_gains g = viewctl_default_gains();
	g.snap_min_rad = 1 * DEG;
	for (int n = 0; n < 20; n++) {
		struct viewctl vc;
		viewctl_init(&vc, &g);
		struct camera c = random_camera(30 * DEG);
		double s0[3], target[3];
		sight(&c, s0);
		/* 10 degrees round: ten frames at most, not 120 */
		double yaw = atan2(s0[0], s0[2]) + 10 * DEG, pitch = asin(s0[1]);
		for (int i = 0; i < 3; i++)
			target[i] = c.xf.p[i];
		target[0] += 3 * cos(pitch) * sin(yaw);
		target[1] += 3 * sin(pitch);
		target[2] += 3 * cos(pitch) * cos(yaw);
		uint64_t t = 0;
		start_snap(&vc, &c, target, t);
		int frames = 0;
		double prev[3];
		sight(&c, prev);
		while (vc.state == VIEWCTL_SNAPPING) {
			t += 8333;
			viewctl_frame(&vc, &c, t);
			frames++;
			double s[3];
			sight(&c, s);
			if (vc.state == VIEWCTL_SNAPPING)
				assert_true(fabs(turn_about_y(prev, s)) >= 1 * DEG - 1e-12);
			memcpy(prev, s, sizeof prev);
		}
		assert_true(frames <= 10);
		double r[3];
		vrp(&c, r);
		assert_vec_near(r, target, 1e-12);
	}
}

static void
test_snap_slow_frames_and_refusals(void **state)
{
	(void)state;
	rng_state = 14;
	struct viewctl_gains g = viewctl_default_gains();
	struct viewctl vc;
	viewctl_init(&vc, &g);
	struct camera c = random_camera(45 * DEG), c0 = c;
	double target[3], r[3];
	random_target(&c, target);

	/* a frame that takes two seconds: one redraw, at the final view */
	start_snap(&vc, &c, target, 100);
	assert_int_equal(viewctl_frame(&vc, &c, 2000100), VIEWCTL_CHANGED);
	assert_int_equal(vc.state, VIEWCTL_VIEWING);
	vrp(&c, r);
	assert_vec_near(r, target, 1e-12);

	/* nothing picked, or a point straight below: no snap, the camera as it was */
	c = c0;
	viewctl_init(&vc, &g);
	enter(&vc, &c, 0);
	feed(&vc, &c, INPUT_KEY, KEY_S, 1);
	assert_int_equal(feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1), VIEWCTL_PICK);
	assert_int_equal(viewctl_snap_to(&vc, &c, NULL, 0), VIEWCTL_TAKEN);
	assert_int_equal(vc.state, VIEWCTL_VIEWING);
	feed(&vc, &c, INPUT_KEY, KEY_S, 1);
	double below[3] = { c.xf.p[0], c.xf.p[1] - 1, c.xf.p[2] };
	assert_int_equal(viewctl_snap_to(&vc, &c, below, 0), VIEWCTL_TAKEN);
	assert_int_equal(vc.state, VIEWCTL_VIEWING);
	assert_same_camera(&c, &c0);
	/* outside the pick, snap_to is not ours */
	assert_int_equal(viewctl_snap_to(&vc, &c, target, 0), VIEWCTL_PASS);

	/* ESC mid-snap ends on the target; C mid-snap goes back to before V */
	viewctl_init(&vc, &g);
	start_snap(&vc, &c, target, 0);
	viewctl_frame(&vc, &c, 300000);
	assert_int_equal(feed(&vc, &c, INPUT_KEY, KEY_ESC, 1), VIEWCTL_ENDED);
	vrp(&c, r);
	assert_vec_near(r, target, 1e-12);
	c = c0;
	viewctl_init(&vc, &g);
	start_snap(&vc, &c, target, 0);
	viewctl_frame(&vc, &c, 300000);
	assert_int_equal(feed(&vc, &c, INPUT_KEY, KEY_C, 1), VIEWCTL_ENDED);
	assert_same_camera(&c, &c0);
}

/* ---- invariants under random use ----------------------------------------------- */

static void
assert_upright_no_twist(const struct camera *c)
{
	const double *r = c->xf.r;
	for (int i = 0; i < 9; i++)
		assert_true(isfinite(r[i]));
	for (int i = 0; i < 3; i++)
		assert_true(isfinite(c->xf.p[i]));
	assert_true(isfinite(c->vrd));
	/* no twist: x horizontal */
	assert_near(r[3], 0, 1e-12);
	/* orthonormal, right-handed, upright */
	for (int a = 0; a < 3; a++)
		for (int b = 0; b < 3; b++) {
			double d = r[a] * r[b] + r[3 + a] * r[3 + b] + r[6 + a] * r[6 + b];
			assert_near(d, a == b, 1e-12);
		}
	double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
		     r[2] * (r[3] * r[7] - r[4] * r[6]);
	assert_near(det, 1, 1e-12);
	assert_true(r[4] > 0);
	/* short of the poles, and in front of its reference point */
	assert_true(fabs(elevation(c)) <= 89 * DEG + 1e-12);
	assert_true(c->vrd >= VIEWOP_VRD_MIN - 1e-15);
}

static void
test_ten_thousand_random_operations(void **state)
{
	(void)state;
	rng_state = 15;
	struct viewctl_gains g = viewctl_default_gains();
	g.rad_per_px = 1 * DEG;
	g.m_per_px = 0.05;
	struct viewctl vc;
	viewctl_init(&vc, &g);
	struct camera c = random_camera(80 * DEG);
	const unsigned buttons[3] = { BTN_LEFT, BTN_MIDDLE, BTN_RIGHT };
	uint64_t t = 0;
	enter(&vc, &c, 0);
	for (int n = 0; n < 10000; n++) {
		double k = urand();
		t += 16667;
		if (k < 0.45) {
			motion(&vc, &c, span(-300, 300), span(-300, 300));
		} else if (k < 0.6) {
			feed(&vc, &c, INPUT_BUTTON, buttons[(int)(urand() * 3)], urand() < 0.5);
		} else if (k < 0.65) {
			feed(&vc, &c, INPUT_KEY, KEY_LEFTCTRL, urand() < 0.5);
		} else if (k < 0.85) {
			/* the operations themselves, with any angle */
			double a = span(-10, 10);
			switch ((int)(urand() * 5)) {
			case 0: viewop_sweep_horizontal(&c, a); break;
			case 1: viewop_sweep_vertical(&c, a); break;
			case 2: viewop_pan_horizontal(&c, a); break;
			case 3: viewop_pan_vertical(&c, a); break;
			default: viewop_zoom(&c, a); break;
			}
		} else if (k < 0.95) {
			/* a snap somewhere, run for a few frames or to the end */
			if (vc.state == VIEWCTL_VIEWING) {
				double target[3] = { span(-10, 10), span(-2, 4), span(-10, 10) };
				feed(&vc, &c, INPUT_KEY, KEY_S, 1);
				feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 1);
				feed(&vc, &c, INPUT_BUTTON, BTN_LEFT, 0);
				viewctl_snap_to(&vc, &c, target, t);
			}
			int frames = (int)(urand() * 80);
			for (int i = 0; i < frames; i++) {
				t += (uint64_t)span(1000, 200000);
				viewctl_frame(&vc, &c, t);
				assert_upright_no_twist(&c);
			}
		} else {
			unsigned keys[3] = { KEY_ESC, KEY_C, KEY_S };
			feed(&vc, &c, INPUT_KEY, keys[(int)(urand() * 3)], 1);
			if (vc.state == VIEWCTL_IDLE)
				enter(&vc, &c, 0);
		}
		assert_upright_no_twist(&c);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sweep_horizontal_is_TDR_about_the_vertical),
		cmocka_unit_test(test_sweep_vertical_is_TDR_about_the_camera_x),
		cmocka_unit_test(test_sweep_vertical_stops_short_of_the_poles),
		cmocka_unit_test(test_pan_horizontal_is_RD_about_the_vertical),
		cmocka_unit_test(test_pan_vertical_is_RD_about_the_camera_x),
		cmocka_unit_test(test_zoom_moves_along_z_keeping_the_reference_point),
		cmocka_unit_test(test_buttons_and_control_select_the_operation),
		cmocka_unit_test(test_the_moving_part_follows_the_pointer),
		cmocka_unit_test(test_v_enters_esc_keeps_c_restores),
		cmocka_unit_test(test_each_view_its_own_camera),
		cmocka_unit_test(test_snap_finishes_within_a_second_at_any_frame_rate),
		cmocka_unit_test(test_snap_in_betweens_are_eased),
		cmocka_unit_test(test_snap_turns_at_least_the_minimum_per_frame),
		cmocka_unit_test(test_snap_slow_frames_and_refusals),
		cmocka_unit_test(test_ten_thousand_random_operations),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
