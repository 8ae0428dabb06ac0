/*
 * test_manip.c - the manipulation operator (Chapter 3, Appendix B) on
 * seeded random cameras and transforms: every row of Table 3.2; the 20
 * degree rule just inside and just outside for the three kinds of
 * motion, and its repeat; a press never moves G; the end of a drag
 * against answers built from where the mouse lines were aimed (a point of
 * the axis, of the plane, of the wheel at a known angle) or the
 * cross-product closed form for a skew line; SHIFT after a rotation.
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
#include "figure/mathx.h"
#include "interact/manip.h"
#include "test_random.h"
#include "test_util.h"

#define TRIALS 50
#define DEG (M_PI / 180.0)

/* a unit vector perpendicular to the unit a */
static void
rand_perp(const double a[3], double dest[3])
{
	double r[3];
	do {
		rand_unit(r);
		double k = mathx_dot(r, a);
		for (int i = 0; i < 3; i++)
			r[i] -= k * a[i];
	} while (mathx_dot(r, r) < 0.01);
	double n = sqrt(mathx_dot(r, r));
	for (int i = 0; i < 3; i++)
		dest[i] = r[i] / n;
}

/* a random rigid transform near the origin */
static void
rand_xform(struct xform *dest)
{
	double a[3], q[4], p[3];
	rand_unit(a);
	mathx_quat_axis_angle(a, span(-M_PI, M_PI), q);
	for (int i = 0; i < 3; i++)
		p[i] = span(-1, 1);
	xform_from_pos_quat(p, q, dest);
}

/* column k of g's rotation: G's axis k in the world */
static void
g_axis(const struct xform *g, int k, double dest[3])
{
	dest[0] = g->r[k];
	dest[1] = g->r[3 + k];
	dest[2] = g->r[6 + k];
}

/* a camera at eye looking at target */
static struct camera
cam_at(const double eye[3], const double target[3])
{
	struct camera c;
	view_camera_default(&c);
	assert_int_equal(view_camera_aim(&c, eye, target), 0);
	return c;
}

/* a camera dist from G's origin whose line of sight makes angle theta with the unit axis a */
static struct camera
cam_at_angle(const struct xform *g, const double a[3], double theta, double dist)
{
	double w[3], eye[3];
	rand_perp(a, w);
	for (int i = 0; i < 3; i++)
		eye[i] = g->p[i] + dist * (cos(theta) * a[i] + sin(theta) * w[i]);
	return cam_at(eye, g->p);
}

/* the mouse line from the camera's eye through world point x */
static struct ray
ray_to(const struct camera *c, const double x[3])
{
	struct ray r;
	double n = 0;
	for (int i = 0; i < 3; i++) {
		r.o[i] = c->xf.p[i];
		r.d[i] = x[i] - c->xf.p[i];
		n += r.d[i] * r.d[i];
	}
	n = sqrt(n);
	for (int i = 0; i < 3; i++)
		r.d[i] /= n;
	return r;
}

/* the mouse line from the eye through a random point within a metre of G's origin */
static struct ray
ray_near(const struct camera *c, const struct xform *g)
{
	double x[3];
	for (int i = 0; i < 3; i++)
		x[i] = g->p[i] + span(-1, 1);
	return ray_to(c, x);
}

/* s of the point of line p + s a nearest line o + t d: the cross-product closed form */
static double
ref_axis_param(const double p[3], const double a[3], const struct ray *r)
{
	double n[3], w[3], c[3];
	mathx_cross(a, r->d, n);
	for (int i = 0; i < 3; i++)
		w[i] = r->o[i] - p[i];
	mathx_cross(w, r->d, c);
	return mathx_dot(c, n) / mathx_dot(n, n);
}

static int
send(struct manip *m, uint8_t kind, uint16_t code, int32_t value)
{
	struct input_event_rec e;
	memset(&e, 0, sizeof e);
	e.kind = kind;
	e.code = code;
	e.value = value;
	return manip_event(m, &e);
}

static int
button(struct manip *m, uint16_t code, int down)
{
	return send(m, INPUT_BUTTON, code, down);
}

static int
key(struct manip *m, uint16_t code, int down)
{
	return send(m, INPUT_KEY, code, down);
}

static const uint16_t btn_of_axis[3] = { BTN_LEFT, BTN_MIDDLE, BTN_RIGHT };

/* presses the chord's buttons (MANIP_LEFT... bits), left to right */
static void
press_buttons(struct manip *m, unsigned buttons)
{
	for (int k = 0; k < 3; k++)
		if (buttons & (1u << k))
			button(m, btn_of_axis[k], 1);
}

static void
assert_xform_near(const struct xform *a, const struct xform *b, double tol)
{
	for (int i = 0; i < 9; i++)
		assert_near(a->r[i], b->r[i], tol);
	for (int i = 0; i < 3; i++)
		assert_near(a->p[i], b->p[i], tol);
}

static void
assert_xform_same(const struct xform *a, const struct xform *b)
{
	assert_memory_equal(a, b, sizeof *a);
}

/* m at g, seen through c, with the default settings */
static void
start(struct manip *m, const struct xform *g, const struct camera *c)
{
	const struct manip_def def = manip_default_def();
	manip_init(m, &def, g, c);
}

/* the hand-worked tests' start: G at the origin, unturned, seen from eye */
static void
start_at_origin(struct manip *m, struct xform *g, struct camera *c, const double eye[3])
{
	xform_identity(g);
	*c = cam_at(eye, g->p);
	start(m, g, c);
}

/* the mouse line from c's eye through x, given to m; returns manip_ray's answer */
static int
mouse_through(struct manip *m, const struct camera *c, const double x[3])
{
	struct ray r = ray_to(c, x);
	return manip_ray(m, &r);
}

/* axis k of the frame in use: G's own under SHIFT, else the world's */
static void
frame_axis(const struct xform *g, int shift, int k, double dest[3])
{
	dest[0] = dest[1] = dest[2] = 0;
	if (shift)
		g_axis(g, k, dest);
	else
		dest[k] = 1;
}

/* the plane left when axis k is left out: its axes u, v (u x v = n) and its normal n */
static void
plane_axes(const struct xform *g, int shift, int k, double u[3], double v[3], double n[3])
{
	frame_axis(g, shift, (k + 1) % 3, u);
	frame_axis(g, shift, (k + 2) % 3, v);
	frame_axis(g, shift, k, n);
}

/* ---- Table 3.2 ----------------------------------------------------------------- */

/*
 * The table as written in section 3.3.2 (with DESIGN.md's erratum: left,
 * middle, right are x, y, z in every row), one line per row.
 */
static const struct {
	int shift, ctrl;
	unsigned buttons;
	enum manip_mode mode;
	int axis; /* the axis, or for a plane the one left out */
} table_3_2[] = {
	{ 0, 0, MANIP_LEFT, MANIP_MODE_LINEAR, 0 },
	{ 0, 0, MANIP_MIDDLE, MANIP_MODE_LINEAR, 1 },
	{ 0, 0, MANIP_RIGHT, MANIP_MODE_LINEAR, 2 },
	{ 0, 0, MANIP_LEFT | MANIP_MIDDLE, MANIP_MODE_PLANAR, 2 },   /* xy */
	{ 0, 0, MANIP_LEFT | MANIP_RIGHT, MANIP_MODE_PLANAR, 1 },    /* xz */
	{ 0, 0, MANIP_MIDDLE | MANIP_RIGHT, MANIP_MODE_PLANAR, 0 },  /* yz */
	{ 0, 1, MANIP_LEFT, MANIP_MODE_ROTATE, 0 },
	{ 0, 1, MANIP_MIDDLE, MANIP_MODE_ROTATE, 1 },
	{ 0, 1, MANIP_RIGHT, MANIP_MODE_ROTATE, 2 },
	{ 1, 0, MANIP_LEFT, MANIP_MODE_LINEAR, 0 },
	{ 1, 0, MANIP_MIDDLE, MANIP_MODE_LINEAR, 1 },
	{ 1, 0, MANIP_RIGHT, MANIP_MODE_LINEAR, 2 },
	{ 1, 0, MANIP_LEFT | MANIP_MIDDLE, MANIP_MODE_PLANAR, 2 },
	{ 1, 0, MANIP_LEFT | MANIP_RIGHT, MANIP_MODE_PLANAR, 1 },
	{ 1, 0, MANIP_MIDDLE | MANIP_RIGHT, MANIP_MODE_PLANAR, 0 },
	{ 1, 1, MANIP_LEFT, MANIP_MODE_ROTATE, 0 },
	{ 1, 1, MANIP_MIDDLE, MANIP_MODE_ROTATE, 1 },
	{ 1, 1, MANIP_RIGHT, MANIP_MODE_ROTATE, 2 },
};

/* every chord: the table's rows, no button idle, and everything else no effect */
static void
test_table_3_2_every_chord(void **unused)
{
	(void)unused;
	for (unsigned b = 0; b < 8; b++)
		for (int shift = 0; shift < 2; shift++)
			for (int ctrl = 0; ctrl < 2; ctrl++) {
				struct manip_selection s = manip_chord(b, shift, ctrl);
				enum manip_mode want = b ? MANIP_MODE_NONE : MANIP_MODE_IDLE;
				int axis = 0;
				for (size_t i = 0; i < sizeof table_3_2 / sizeof table_3_2[0]; i++)
					if (table_3_2[i].buttons == b && table_3_2[i].shift == shift &&
					    table_3_2[i].ctrl == ctrl) {
						want = table_3_2[i].mode;
						axis = table_3_2[i].axis;
					}
				assert_int_equal(s.mode, want);
				if (want != MANIP_MODE_IDLE && want != MANIP_MODE_NONE) {
					assert_int_equal(s.axis, axis);
					assert_int_equal(s.frame, shift ? MANIP_LOCAL : MANIP_GLOBAL);
				}
			}
}

/*
 * The same rows reached through events, from a camera that sees every
 * axis at 54.7 degrees (nothing refused): the state, and the icon's axis
 * in the world (G's columns under SHIFT).
 */
static void
test_table_3_2_through_events(void **unused)
{
	(void)unused;
	rng_state = 1;
	struct xform g;
	rand_xform(&g);
	for (size_t i = 0; i < sizeof table_3_2 / sizeof table_3_2[0]; i++) {
		/* the eye along (1,1,1) of the frame in use: 54.7 degrees from each of its axes */
		double eye[3], d[3] = { 1, 1, 1 };
		if (table_3_2[i].shift)
			xform_rotate(&g, (double[3]){ 1, 1, 1 }, d);
		for (int k = 0; k < 3; k++)
			eye[k] = g.p[k] + 3 * d[k];
		struct camera c = cam_at(eye, g.p);
		struct manip m;
		start(&m, &g, &c);
		if (table_3_2[i].shift)
			assert_int_equal(key(&m, KEY_RIGHTSHIFT, 1), 1);
		if (table_3_2[i].ctrl)
			assert_int_equal(key(&m, KEY_LEFTCTRL, 1), 1);
		for (int k = 0; k < 3; k++)
			if (table_3_2[i].buttons & (1u << k))
				assert_int_equal(button(&m, btn_of_axis[k], 1), 1);
		static const enum manip_state of_mode[] = {
			[MANIP_MODE_LINEAR] = MANIP_LINEAR,
			[MANIP_MODE_PLANAR] = MANIP_PLANAR,
			[MANIP_MODE_ROTATE] = MANIP_ROTATE,
		};
		assert_int_equal(m.state, of_mode[table_3_2[i].mode]);
		struct manip_icon icon;
		manip_icon(&m, &icon);
		double want[3] = { 0, 0, 0 };
		if (table_3_2[i].shift)
			g_axis(&g, table_3_2[i].axis, want);
		else
			want[table_3_2[i].axis] = 1;
		for (int k = 0; k < 3; k++)
			assert_near(icon.axis[k], want[k], 1e-12);
		/* the plane's axes, or the wheel's, are the two other ones */
		assert_near(mathx_dot(icon.u, icon.axis), 0, 1e-12);
		assert_near(mathx_dot(icon.v, icon.axis), 0, 1e-12);
		assert_near(mathx_dot(icon.u, icon.v), 0, 1e-12);
	}
}

/* three buttons, and CONTROL with two, do nothing: G stays under any mouse line */
static void
test_three_buttons_and_control_with_two_do_nothing(void **unused)
{
	(void)unused;
	rng_state = 2;
	for (int ctrl = 0; ctrl < 2; ctrl++) {
		struct xform g;
		rand_xform(&g);
		struct camera c = cam_at((double[3]){ 3, 3, 3 }, g.p);
		struct manip m;
		start(&m, &g, &c);
		struct ray r = ray_near(&c, &g);
		manip_ray(&m, &r);
		if (ctrl)
			key(&m, KEY_RIGHTCTRL, 1);
		button(&m, BTN_LEFT, 1);
		button(&m, BTN_RIGHT, 1);
		if (!ctrl)
			button(&m, BTN_MIDDLE, 1);
		assert_int_equal(m.state, MANIP_NONE);
		for (int k = 0; k < 10; k++) {
			r = ray_near(&c, &g);
			assert_int_equal(manip_ray(&m, &r), 0);
		}
		assert_xform_same(&m.g, &g);
	}
}

/* repeats, presses of what is down, other keys and kinds change nothing */
static void
test_events_that_change_nothing(void **unused)
{
	(void)unused;
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, (double[3]){ 3, 3, 3 });
	assert_int_equal(key(&m, KEY_LEFTSHIFT, 1), 1);
	assert_int_equal(key(&m, KEY_LEFTSHIFT, 2), 0);
	assert_int_equal(key(&m, KEY_LEFTSHIFT, 1), 0);
	assert_int_equal(key(&m, KEY_A, 1), 0);
	assert_int_equal(button(&m, BTN_SIDE, 1), 0);
	assert_int_equal(send(&m, INPUT_MOTION, 0, 0), 0);
	/* the other SHIFT held: releasing one keeps SHIFT */
	assert_int_equal(key(&m, KEY_RIGHTSHIFT, 1), 1);
	assert_int_equal(key(&m, KEY_LEFTSHIFT, 0), 1);
	button(&m, BTN_LEFT, 1);
	assert_int_equal(m.sel.frame, MANIP_LOCAL);
	assert_int_equal(key(&m, KEY_RIGHTSHIFT, 0), 1);
	assert_int_equal(m.sel.frame, MANIP_GLOBAL);
}

/* ---- the 20 degree rule ---------------------------------------------------------- */

/*
 * One selection seen from a camera whose line of sight (eye to G's
 * origin) makes angle theta with the selection's axis (or normal).
 * Returns the state after the press and checks G then stays put if it
 * was refused.
 */
static enum manip_state
press_at_angle(int shift, int ctrl, unsigned buttons, int axis, double theta)
{
	struct xform g;
	rand_xform(&g);
	double a[3];
	frame_axis(&g, shift, axis, a);
	struct camera c = cam_at_angle(&g, a, theta, span(1, 6));
	struct manip m;
	start(&m, &g, &c);
	struct ray r = ray_near(&c, &g);
	manip_ray(&m, &r);
	if (shift)
		key(&m, KEY_LEFTSHIFT, 1);
	if (ctrl)
		key(&m, KEY_LEFTCTRL, 1);
	press_buttons(&m, buttons);
	const struct manip_refusal *no = manip_refusal(&m);
	if (m.state == MANIP_REFUSED) {
		assert_int_equal(no->active, 1);
		assert_int_equal(no->repeat, 0);
		assert_near(no->angle, theta <= M_PI / 2 ? theta : M_PI - theta, 1e-9);
		assert_near(fabs(mathx_dot(no->axis, a)), 1, 1e-12);
		for (int k = 0; k < 10; k++) {
			r = ray_near(&c, &g);
			assert_int_equal(manip_ray(&m, &r), 0);
		}
		assert_xform_same(&m.g, &g);
	} else {
		assert_int_equal(no->active, 0);
	}
	return m.state;
}

/* the point (a, b) of the plane through o spanned by u and v */
static void
plane_point(const double o[3], const double u[3], const double v[3], double a, double b,
	    double dest[3])
{
	for (int e = 0; e < 3; e++)
		dest[e] = o[e] + a * u[e] + b * v[e];
}

/* the point of the wheel about o in the plane of u and v at radius rad, angle th from u */
static void
wheel_point(const double o[3], const double u[3], const double v[3], double rad, double th,
	    double dest[3])
{
	for (int e = 0; e < 3; e++)
		dest[e] = o[e] + rad * (cos(th) * u[e] + sin(th) * v[e]);
}

/* an angle between the line of sight and the selection's axis (or normal); the state it gives */
struct angle_case {
	double theta;
	enum manip_state want;
};

/*
 * Every case for each axis k of either frame, TRIALS times: a single
 * button for k (with CONTROL, the wheel), or for a plane the two buttons
 * other than its normal k's. either_end draws, once per axis, whether
 * the angles count from the axis toward the eye or from the far end of it.
 */
static void
assert_presses_at_angles(int ctrl, int plane, int either_end, const struct angle_case *cases,
			 size_t ncases)
{
	for (int t = 0; t < TRIALS; t++)
		for (int shift = 0; shift < 2; shift++)
			for (int k = 0; k < 3; k++) {
				unsigned b = plane ? 7u & ~(1u << k) : 1u << k;
				double off = either_end && urand() >= 0.5 ? M_PI : 0;
				double s = off ? -1 : 1;
				for (size_t i = 0; i < ncases; i++)
					assert_int_equal(press_at_angle(shift, ctrl, b, k,
									off + s * cases[i].theta),
							 cases[i].want);
			}
}

/* G at the origin seen from eye: CONTROL if ctrl, then the buttons; refused, with that message */
static void
assert_refused_with(const double eye[3], int ctrl, unsigned buttons, const char *message)
{
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, eye);
	if (ctrl)
		key(&m, KEY_LEFTCTRL, 1);
	press_buttons(&m, buttons);
	assert_int_equal(m.state, MANIP_REFUSED);
	assert_string_equal(manip_refusal(&m)->message, message);
}

static void
test_20_degree_rule_translation_along_an_axis(void **unused)
{
	(void)unused;
	static const struct angle_case cases[] = {
		{ 19 * DEG, MANIP_REFUSED },
		{ 21 * DEG, MANIP_LINEAR },
	};
	rng_state = 3;
	/* toward the eye or away from it alike */
	assert_presses_at_angles(0, 0, 1, cases, sizeof cases / sizeof cases[0]);
	/* and the message */
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, (double[3]){ 5, 0.1, 0 });
	button(&m, BTN_LEFT, 1);
	assert_string_equal(manip_refusal(&m)->message,
			    "can't translate along that axis from this view");
}

/* the wheel within 20 degrees of edge-on: the axis 71 degrees from the line of sight */
static void
test_20_degree_rule_rotation(void **unused)
{
	(void)unused;
	static const struct angle_case cases[] = {
		{ 71 * DEG, MANIP_REFUSED },
		{ 109 * DEG, MANIP_REFUSED },
		{ 69 * DEG, MANIP_ROTATE },
		{ 0, MANIP_ROTATE },
	};
	rng_state = 4;
	assert_presses_at_angles(1, 0, 0, cases, sizeof cases / sizeof cases[0]);
	assert_refused_with((double[3]){ 0, 0.1, 5 }, 1, MANIP_LEFT,
			    "can't rotate around that axis from this view");
}

/* the plane within 20 degrees of edge-on: its normal 71 degrees from the line of sight */
static void
test_20_degree_rule_planar(void **unused)
{
	(void)unused;
	static const struct angle_case cases[] = {
		{ 71 * DEG, MANIP_REFUSED },
		{ 69 * DEG, MANIP_PLANAR },
		{ 180 * DEG, MANIP_PLANAR },
	};
	rng_state = 5;
	assert_presses_at_angles(0, 1, 0, cases, sizeof cases / sizeof cases[0]);
	assert_refused_with((double[3]){ 0, 0.1, 5 }, 0, MANIP_LEFT | MANIP_RIGHT,
			    "can't translate in that plane from this view");
}

/*
 * Choosing the refused axis again is the trigger of the view adjustment;
 * any action in between forgets it, and a camera that moves clear of the
 * axis turns the held button into a drag.
 */
static void
test_refusal_repeat_and_the_camera_hook(void **unused)
{
	(void)unused;
	struct xform g;
	xform_identity(&g);
	/* looking down z: z is degenerate, x is fine */
	struct camera c = cam_at((double[3]){ 0, 0, 5 }, g.p);
	struct manip m;
	start(&m, &g, &c);
	button(&m, BTN_RIGHT, 1);
	assert_int_equal(m.state, MANIP_REFUSED);
	assert_int_equal(manip_refusal(&m)->repeat, 0);
	assert_int_equal(manip_refusal(&m)->sel.axis, 2);
	button(&m, BTN_RIGHT, 0);
	assert_int_equal(manip_refusal(&m)->active, 0);
	button(&m, BTN_RIGHT, 1);
	assert_int_equal(m.state, MANIP_REFUSED);
	assert_int_equal(manip_refusal(&m)->repeat, 1);
	/* an accepted axis in between: the next refusal is a first one again */
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_LEFT, 1);
	assert_int_equal(m.state, MANIP_LINEAR);
	button(&m, BTN_LEFT, 0);
	button(&m, BTN_RIGHT, 1);
	assert_int_equal(manip_refusal(&m)->repeat, 0);
	/* a different refused selection is not a repeat either */
	button(&m, BTN_RIGHT, 0);
	key(&m, KEY_LEFTCTRL, 1);
	button(&m, BTN_LEFT, 1); /* rotating about x, seen edge-on */
	assert_int_equal(m.state, MANIP_REFUSED);
	assert_int_equal(manip_refusal(&m)->repeat, 0);
	key(&m, KEY_LEFTCTRL, 0);
	button(&m, BTN_LEFT, 0);

	/* the view turns 30 degrees away from z under the held button: it drags, without a jump */
	button(&m, BTN_RIGHT, 1);
	assert_int_equal(m.state, MANIP_REFUSED);
	struct camera c2 = cam_at((double[3]){ 5 * sin(30 * DEG), 0, 5 * cos(30 * DEG) }, g.p);
	manip_camera(&m, &c2);
	assert_int_equal(m.state, MANIP_LINEAR);
	assert_int_equal(manip_refusal(&m)->active, 0);
	struct ray r0 = ray_to(&c2, (double[3]){ 0.3, 0.2, 0 });
	assert_int_equal(manip_ray(&m, &r0), 0);
	assert_xform_same(&m.g, &g);
	/* then a line through the axis point z = 0.4 */
	struct ray r = ray_to(&c2, (double[3]){ 0, 0, 0.4 });
	assert_int_equal(manip_ray(&m, &r), 1);
	const double z[3] = { 0, 0, 1 };
	assert_near(m.g.p[0], 0, 0);
	assert_near(m.g.p[1], 0, 0);
	assert_near(m.g.p[2], 0.4 - ref_axis_param(g.p, z, &r0), 1e-9);
}

/*
 * The line of sight is the line from the eye to G's origin, not the
 * camera's -z: G off the centre of the screen, seen 10 degrees from z
 * while the camera looks 30 degrees from z, cannot move along z; and the
 * other way round it can.
 */
static void
test_line_of_sight_runs_from_the_eye_to_g(void **unused)
{
	(void)unused;
	struct xform g;
	xform_identity(&g);
	for (int flip = 0; flip < 2; flip++) {
		double to_g = (flip ? 30 : 10) * DEG, look = (flip ? 10 : 30) * DEG;
		double eye[3] = { 5 * sin(to_g), 0, 5 * cos(to_g) };
		double target[3] = { eye[0] - sin(look), 0, eye[2] - cos(look) };
		struct camera c = cam_at(eye, target);
		struct manip m;
		start(&m, &g, &c);
		button(&m, BTN_RIGHT, 1);
		assert_int_equal(m.state, flip ? MANIP_LINEAR : MANIP_REFUSED);
	}
}

/* ---- a press never moves G ---------------------------------------------------------- */

/*
 * Press anywhere: G unchanged; change the buttons mid-drag: unchanged
 * again; only mouse lines move it.
 */
static void
test_a_press_never_moves_g(void **unused)
{
	(void)unused;
	rng_state = 6;
	int acting = 0;
	for (int t = 0; t < TRIALS; t++) {
		struct xform g;
		rand_xform(&g);
		/*
		 * a view that refuses nothing at first: the eye near the (1,1,1)
		 * diagonal, 45..65 degrees from the global axes, and G turned
		 * about that line, so its own axes keep those angles
		 */
		double d[3], eye[3], q[4];
		for (int k = 0; k < 3; k++)
			d[k] = 1 + span(-0.2, 0.2);
		double n = sqrt(mathx_dot(d, d));
		for (int k = 0; k < 3; k++)
			d[k] /= n;
		mathx_quat_axis_angle(d, span(-M_PI, M_PI), q);
		mathx_quat_to_mat(q, g.r);
		for (int k = 0; k < 3; k++)
			eye[k] = g.p[k] + 4 * d[k];
		struct camera c = cam_at(eye, g.p);
		struct manip m;
		start(&m, &g, &c);
		struct ray r = ray_near(&c, &g);
		manip_ray(&m, &r);
		/* a chord sequence through every kind of motion, a mouse line between changes */
		static const struct {
			uint8_t kind;
			uint16_t code;
		} seq[] = {
			{ INPUT_BUTTON, BTN_LEFT },   { INPUT_BUTTON, BTN_MIDDLE },
			{ INPUT_KEY, KEY_LEFTSHIFT }, { INPUT_BUTTON, BTN_LEFT },
			{ INPUT_KEY, KEY_LEFTCTRL },  { INPUT_BUTTON, BTN_RIGHT },
			{ INPUT_KEY, KEY_LEFTSHIFT }, { INPUT_BUTTON, BTN_MIDDLE },
			{ INPUT_BUTTON, BTN_RIGHT },  { INPUT_KEY, KEY_LEFTCTRL },
		};
		unsigned down = 0;
		for (size_t i = 0; i < sizeof seq / sizeof seq[0]; i++) {
			struct xform before = m.g;
			/* each code presses at its first mention and releases at its second */
			unsigned id = 1u << (seq[i].code & 31);
			int is_down = !(down & id);
			down ^= id;
			send(&m, seq[i].kind, seq[i].code, is_down);
			/* G may have turned or moved toward a refused view: G stays then too */
			acting += m.state == MANIP_LINEAR || m.state == MANIP_PLANAR ||
				  m.state == MANIP_ROTATE;
			assert_xform_same(&m.g, &before);
			r = ray_near(&c, &g);
			manip_ray(&m, &r);
		}
		assert_int_equal(m.state, MANIP_IDLE);
	}
	/* most presses chose a motion (a refusal proves nothing about anchoring) */
	assert_true(acting > TRIALS * 5);
}

/* ---- the drags --------------------------------------------------------------------- */

/*
 * A camera 35..55 degrees from the unit axis a, 3..6 m from G's origin:
 * a drag of half a metre keeps the line of sight clear of the 20 degree rule.
 */
static struct camera
cam_oblique(const struct xform *g, const double a[3])
{
	double theta = span(35, 55) * DEG * (urand() < 0.5 ? 1 : -1) + (urand() < 0.5 ? 0 : M_PI);
	return cam_at_angle(g, a, theta, span(3, 6));
}

/*
 * B.1: the anchor line goes through G's origin, so G's origin ends on
 * the point of the axis nearest the last mouse line (a skew one, from
 * the closed form); then a press elsewhere and a drag move G by the
 * difference of the nearest points only.
 */
static void
test_linear_translation(void **unused)
{
	(void)unused;
	rng_state = 7;
	for (int t = 0; t < TRIALS; t++)
		for (int shift = 0; shift < 2; shift++)
			for (int k = 0; k < 3; k++) {
				struct xform g;
				rand_xform(&g);
				double a[3];
				frame_axis(&g, shift, k, a);
				struct camera c = cam_oblique(&g, a);
				struct manip m;
				start(&m, &g, &c);
				struct ray r = ray_to(&c, g.p);
				manip_ray(&m, &r);
				if (shift)
					key(&m, KEY_LEFTSHIFT, 1);
				button(&m, btn_of_axis[k], 1);
				assert_int_equal(m.state, MANIP_LINEAR);
				for (int i = 0; i < 5; i++) {
					double x[3];
					double s = span(-0.5, 0.5);
					for (int j = 0; j < 3; j++)
						x[j] = g.p[j] + s * a[j] + span(-0.05, 0.05);
					r = ray_to(&c, x);
					manip_ray(&m, &r);
				}
				double s1 = ref_axis_param(g.p, a, &r);
				for (int j = 0; j < 3; j++)
					assert_near(m.g.p[j], g.p[j] + s1 * a[j], 1e-9);
				for (int j = 0; j < 9; j++)
					assert_near(m.g.r[j], g.r[j], 0);

				/* release; press again elsewhere; drag */
				button(&m, btn_of_axis[k], 0);
				struct xform g1 = m.g;
				struct ray r0 = ray_near(&c, &g1);
				manip_ray(&m, &r0);
				button(&m, btn_of_axis[k], 1);
				assert_xform_same(&m.g, &g1);
				assert_int_equal(m.state, MANIP_LINEAR);
				struct ray r2 = ray_near(&c, &g1);
				manip_ray(&m, &r2);
				double d = ref_axis_param(g1.p, a, &r2) - ref_axis_param(g1.p, a, &r0);
				for (int j = 0; j < 3; j++)
					assert_near(m.g.p[j], g1.p[j] + d * a[j], 1e-9);
			}
}

/* B.2: mouse lines through known points of the plane move G by their difference */
static void
test_planar_translation(void **unused)
{
	(void)unused;
	rng_state = 8;
	for (int t = 0; t < TRIALS; t++)
		for (int shift = 0; shift < 2; shift++)
			for (int k = 0; k < 3; k++) {
				struct xform g;
				rand_xform(&g);
				/* the plane's axes i, j and its normal */
				int i = (k + 1) % 3, j = (k + 2) % 3;
				double u[3], v[3], n[3];
				plane_axes(&g, shift, k, u, v, n);
				struct camera c = cam_oblique(&g, n);
				struct manip m;
				start(&m, &g, &c);
				double a0 = span(-1, 1), b0 = span(-1, 1), x0[3];
				plane_point(g.p, u, v, a0, b0, x0);
				struct ray r = ray_to(&c, x0);
				manip_ray(&m, &r);
				if (shift)
					key(&m, KEY_RIGHTSHIFT, 1);
				button(&m, btn_of_axis[i], 1);
				assert_xform_same(&m.g, &g);
				button(&m, btn_of_axis[j], 1);
				assert_int_equal(m.state, MANIP_PLANAR);
				assert_xform_same(&m.g, &g);
				double a1 = 0, b1 = 0;
				for (int step = 0; step < 4; step++) {
					double x1[3];
					a1 = span(-1, 1);
					b1 = span(-1, 1);
					plane_point(g.p, u, v, a1, b1, x1);
					r = ray_to(&c, x1);
					manip_ray(&m, &r);
				}
				for (int e = 0; e < 3; e++)
					assert_near(m.g.p[e],
						    g.p[e] + (a1 - a0) * u[e] + (b1 - b0) * v[e], 1e-9);
				for (int e = 0; e < 9; e++)
					assert_near(m.g.r[e], g.r[e], 0);
			}
}

/* R about the unit axis a by angle, from the quaternion route */
static void
ref_rotation(const double a[3], double angle, double dest[9])
{
	double q[4];
	mathx_quat_axis_angle(a, angle, q);
	mathx_quat_to_mat(q, dest);
}

/*
 * B.3: mouse lines through wheel points at known angles (small steps,
 * through more than a turn): G' = R G about the axis through G's origin,
 * by the angle from the first spoke to the last; the origin stays.
 */
static void
test_rotation(void **unused)
{
	(void)unused;
	rng_state = 9;
	for (int t = 0; t < TRIALS; t++)
		for (int shift = 0; shift < 2; shift++)
			for (int k = 0; k < 3; k++) {
				struct xform g;
				rand_xform(&g);
				double u[3], v[3], a[3];
				plane_axes(&g, shift, k, u, v, a);
				/* u x v = a: angles in the wheel are counterclockwise about a */
				struct camera c = cam_at_angle(&g, a, span(0, 60) * DEG, span(2, 6));
				struct manip m;
				start(&m, &g, &c);
				double th0 = span(-M_PI, M_PI), rad = span(0.2, 1), x[3];
				wheel_point(g.p, u, v, rad, th0, x);
				struct ray r = ray_to(&c, x);
				manip_ray(&m, &r);
				if (shift)
					key(&m, KEY_LEFTSHIFT, 1);
				key(&m, KEY_RIGHTCTRL, 1);
				button(&m, btn_of_axis[k], 1);
				assert_int_equal(m.state, MANIP_ROTATE);
				assert_xform_same(&m.g, &g);
				/* the icon has its first spoke before any motion */
				struct manip_icon icon;
				manip_icon(&m, &icon);
				assert_int_equal(icon.has_spokes, 1);
				for (int e = 0; e < 3; e++)
					assert_near(icon.spoke0[e], x[e] - g.p[e], 1e-9);
				double turn = span(-3 * M_PI, 3 * M_PI);
				int steps = 40;
				for (int s = 1; s <= steps; s++) {
					double th = th0 + turn * s / steps, rr = span(0.2, 1);
					wheel_point(g.p, u, v, rr, th, x);
					r = ray_to(&c, x);
					manip_ray(&m, &r);
				}
				double rot[9];
				struct xform want;
				ref_rotation(a, turn, rot);
				mathx_mat3_mul(rot, g.r, want.r);
				memcpy(want.p, g.p, sizeof want.p);
				assert_xform_near(&m.g, &want, 1e-9);
				assert_near(m.g.p[0], g.p[0], 0);
				assert_near(m.g.p[1], g.p[1], 0);
				assert_near(m.g.p[2], g.p[2], 0);
				manip_icon(&m, &icon);
				assert_near(icon.angle, turn, 1e-9);
				for (int e = 0; e < 3; e++)
					assert_near(icon.spoke[e], x[e] - g.p[e], 1e-9);
			}
}

/*
 * A change of buttons mid-drag re-anchors: x, then the xy plane, then
 * back to x: no jump at either change, and each stretch moves G by the
 * change of its own reference since the change.
 */
static void
test_change_of_buttons_mid_drag(void **unused)
{
	(void)unused;
	rng_state = 10;
	for (int t = 0; t < TRIALS; t++) {
		struct xform g;
		xform_identity(&g);
		for (int e = 0; e < 3; e++)
			g.p[e] = span(-1, 1);
		/* 45 degrees from x, y and z alike enough: eye along (1, 1.2, 1.4) */
		double eye[3] = { g.p[0] + 3, g.p[1] + 3.6, g.p[2] + 4.2 };
		struct camera c = cam_at(eye, g.p);
		struct manip m;
		start(&m, &g, &c);
		struct ray r = ray_near(&c, &g);
		manip_ray(&m, &r);
		button(&m, BTN_LEFT, 1);
		struct ray r1 = ray_near(&c, &g);
		manip_ray(&m, &r1);
		struct xform g1 = m.g;
		const double x[3] = { 1, 0, 0 };
		double want = ref_axis_param(g.p, x, &r1) - ref_axis_param(g.p, x, &r);
		assert_near(g1.p[0], g.p[0] + want, 1e-9);
		/* middle joins: planar xy from here */
		button(&m, BTN_MIDDLE, 1);
		assert_int_equal(m.state, MANIP_PLANAR);
		assert_xform_same(&m.g, &g1);
		struct ray r2 = ray_near(&c, &g);
		manip_ray(&m, &r2);
		/* the xy plane through g1: z = g1.p[2] */
		double h1 = (g1.p[2] - r1.o[2]) / r1.d[2], h2 = (g1.p[2] - r2.o[2]) / r2.d[2];
		for (int e = 0; e < 2; e++)
			assert_near(m.g.p[e], g1.p[e] + (r2.o[e] + h2 * r2.d[e]) - (r1.o[e] + h1 * r1.d[e]),
				    1e-9);
		assert_near(m.g.p[2], g1.p[2], 1e-12);
		struct xform g2 = m.g;
		/* left lets go: linear along y from here */
		button(&m, BTN_LEFT, 0);
		assert_int_equal(m.state, MANIP_LINEAR);
		assert_xform_same(&m.g, &g2);
		struct ray r3 = ray_near(&c, &g);
		manip_ray(&m, &r3);
		const double y[3] = { 0, 1, 0 };
		want = ref_axis_param(g2.p, y, &r3) - ref_axis_param(g2.p, y, &r2);
		assert_near(m.g.p[0], g2.p[0], 1e-12);
		assert_near(m.g.p[1], g2.p[1] + want, 1e-9);
		assert_near(m.g.p[2], g2.p[2], 1e-12);
	}
}

/* a camera that moves mid-drag does not move G; the next mouse line re-anchors */
static void
test_camera_change_mid_drag(void **unused)
{
	(void)unused;
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, (double[3]){ 3, 3, 4 });
	mouse_through(&m, &c, (double[3]){ 0, 0, 0 });
	button(&m, BTN_LEFT, 1);
	button(&m, BTN_RIGHT, 1); /* the floor plane, xz */
	mouse_through(&m, &c, (double[3]){ 0.5, 0, 0.25 });
	assert_near(m.g.p[0], 0.5, 1e-9);
	assert_near(m.g.p[2], 0.25, 1e-9);
	/* the view swings round; the mouse line from the same pixel now meets the floor elsewhere */
	struct camera c2 = cam_at((double[3]){ -2, 3, 3 }, g.p);
	manip_camera(&m, &c2);
	assert_int_equal(m.state, MANIP_PLANAR);
	assert_int_equal(mouse_through(&m, &c2, (double[3]){ 1.5, 0, -1 }), 0);
	assert_near(m.g.p[0], 0.5, 1e-9);
	mouse_through(&m, &c2, (double[3]){ 1.75, 0, -0.5 });
	assert_near(m.g.p[0], 0.75, 1e-9);
	assert_near(m.g.p[1], 0, 1e-12);
	assert_near(m.g.p[2], 0.75, 1e-9);
}

/*
 * SHIFT after a rotation: turn G 90 degrees about global y by cranking
 * the wheel, then SHIFT + left translates along G's x, which is now
 * global -z.
 */
static void
test_shift_uses_local_axes_after_a_rotation(void **unused)
{
	(void)unused;
	struct xform g;
	xform_identity(&g);
	g.p[1] = 1;
	/* from above and to the side: y 40 degrees from the line of sight, x and z well clear */
	double eye[3] = { 3 * sin(40 * DEG) * cos(30 * DEG), 1 + 3 * cos(40 * DEG),
			  3 * sin(40 * DEG) * sin(30 * DEG) };
	struct camera c = cam_at(eye, g.p);
	struct manip m;
	start(&m, &g, &c);
	/* the wheel about y lies in the xz plane at height 1; spokes at angles about +y: z toward x */
	mouse_through(&m, &c, (double[3]){ 0, 1, 0.5 });
	key(&m, KEY_LEFTCTRL, 1);
	button(&m, BTN_MIDDLE, 1);
	assert_int_equal(m.state, MANIP_ROTATE);
	for (int s = 1; s <= 9; s++) {
		double th = 10 * s * DEG;
		mouse_through(&m, &c, (double[3]){ 0.5 * sin(th), 1, 0.5 * cos(th) });
	}
	button(&m, BTN_MIDDLE, 0);
	key(&m, KEY_LEFTCTRL, 0);
	/* G's x after 90 degrees about +y is -z */
	assert_near(m.g.r[0], 0, 1e-9);
	assert_near(m.g.r[3], 0, 1e-9);
	assert_near(m.g.r[6], -1, 1e-9);
	key(&m, KEY_LEFTSHIFT, 1);
	button(&m, BTN_LEFT, 1);
	assert_int_equal(m.state, MANIP_LINEAR);
	struct manip_icon icon;
	manip_icon(&m, &icon);
	assert_near(icon.axis[2], -1, 1e-9);
	/* lines through two points of G's x axis 0.3 apart move G 0.3 along it */
	mouse_through(&m, &c, (double[3]){ 0, 1, 0.1 });
	struct xform g1 = m.g;
	mouse_through(&m, &c, (double[3]){ 0, 1, -0.2 });
	assert_near(m.g.p[0], g1.p[0], 1e-9);
	assert_near(m.g.p[1], g1.p[1], 1e-9);
	assert_near(m.g.p[2], g1.p[2] - 0.3, 1e-9);
	assert_near(g1.p[0], 0, 1e-9);
	assert_near(g1.p[1], 1, 1e-9);
	/* without SHIFT, left is global x again */
	key(&m, KEY_LEFTSHIFT, 0);
	manip_icon(&m, &icon);
	assert_near(icon.axis[0], 1, 0);
}

/*
 * ALT: a tenth of the motion, counted from the moment it changes, so
 * neither pressing nor releasing it moves G; and it selects nothing, so
 * holding it over a refused axis is not a repeat.
 */
static void
test_alt_gives_a_tenth(void **unused)
{
	(void)unused;
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, (double[3]){ 3, 3, 4 });
	mouse_through(&m, &c, (double[3]){ 0, 0, 0 });
	button(&m, BTN_LEFT, 1);
	mouse_through(&m, &c, (double[3]){ 0.5, 0, 0 });
	assert_near(m.g.p[0], 0.5, 1e-9);
	assert_int_equal(key(&m, KEY_LEFTALT, 1), 1);
	assert_near(m.g.p[0], 0.5, 1e-9);
	mouse_through(&m, &c, (double[3]){ 1.5, 0, 0 });
	assert_near(m.g.p[0], 0.6, 1e-9);
	assert_int_equal(key(&m, KEY_LEFTALT, 0), 1);
	assert_near(m.g.p[0], 0.6, 1e-9);
	mouse_through(&m, &c, (double[3]){ 1.0, 0, 0 });
	assert_near(m.g.p[0], 0.1, 1e-9);
	assert_near(m.g.p[1], 0, 1e-12);
	assert_near(m.g.p[2], 0, 1e-12);
	button(&m, BTN_LEFT, 0);

	/* looking down z: z refused; ALT over it is no second choice, pressing z again is */
	struct camera down_z = cam_at((double[3]){ 0.1, 0, 5 }, m.g.p);
	manip_camera(&m, &down_z);
	button(&m, BTN_RIGHT, 1);
	assert_int_equal(m.state, MANIP_REFUSED);
	key(&m, KEY_RIGHTALT, 1);
	assert_int_equal(m.state, MANIP_REFUSED);
	assert_int_equal(manip_refusal(&m)->repeat, 0);
	key(&m, KEY_RIGHTALT, 0);
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_RIGHT, 1);
	assert_int_equal(manip_refusal(&m)->repeat, 1);
}

/* increments: 1 cm along each axis, 5 degrees of turn, counted from the anchor */
static void
test_increments(void **unused)
{
	(void)unused;
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, (double[3]){ 3, 3, 4 });
	manip_increments(&m, 1);
	mouse_through(&m, &c, (double[3]){ 0, 0, 0 });
	button(&m, BTN_LEFT, 1);
	mouse_through(&m, &c, (double[3]){ 0.123, 0, 0 });
	assert_near(m.g.p[0], 0.12, 1e-12);
	mouse_through(&m, &c, (double[3]){ 0.126, 0, 0 });
	assert_near(m.g.p[0], 0.13, 1e-12);
	/* the floor plane, steps along x and z from where the last line met it */
	button(&m, BTN_RIGHT, 1);
	mouse_through(&m, &c, (double[3]){ 0.126 + 0.123, 0, -0.456 });
	assert_near(m.g.p[0], 0.25, 1e-12);
	assert_near(m.g.p[1], 0, 0);
	assert_near(m.g.p[2], -0.46, 1e-12);
	button(&m, BTN_LEFT, 0);
	button(&m, BTN_RIGHT, 0);

	/* the wheel about y, cranked 47 then 48 degrees: 45 then 50 */
	const double o[3] = { m.g.p[0], 0, m.g.p[2] };
	mouse_through(&m, &c, (double[3]){ o[0], 0, o[2] + 0.5 });
	key(&m, KEY_LEFTCTRL, 1);
	button(&m, BTN_MIDDLE, 1);
	for (int deg = 47; deg <= 48; deg++) {
		for (int s = 1; s <= 10; s++) {
			double th = deg * DEG * s / 10;
			mouse_through(&m, &c,
				      (double[3]){ o[0] + 0.5 * sin(th), 0, o[2] + 0.5 * cos(th) });
		}
		double want[9];
		mathx_rot_y((deg == 47 ? 45 : 50) * DEG, want);
		for (int i = 0; i < 9; i++)
			assert_near(m.g.r[i], want[i], 1e-12);
		assert_near(m.g.p[0], o[0], 0);
		assert_near(m.g.p[2], o[2], 0);
		/* back to the first spoke for the next round */
		for (int s = 9; s >= 0; s--) {
			double th = deg * DEG * s / 10;
			mouse_through(&m, &c,
				      (double[3]){ o[0] + 0.5 * sin(th), 0, o[2] + 0.5 * cos(th) });
		}
		assert_near(m.g.r[0], 1, 1e-12);
	}
	/* turning increments off mid-drag moves nothing; the rest is free */
	struct xform before = m.g;
	manip_increments(&m, 0);
	assert_xform_same(&m.g, &before);
	double th = 47 * DEG;
	mouse_through(&m, &c, (double[3]){ o[0] + 0.5 * sin(th), 0, o[2] + 0.5 * cos(th) });
	double want[9];
	mathx_rot_y(th, want);
	for (int i = 0; i < 9; i++)
		assert_near(m.g.r[i], want[i], 1e-9);
}

/* G set from outside mid-drag (a snap): kept, and the drag goes on from there */
static void
test_set_mid_drag(void **unused)
{
	(void)unused;
	struct xform g;
	struct camera c;
	struct manip m;
	start_at_origin(&m, &g, &c, (double[3]){ 3, 3, 4 });
	mouse_through(&m, &c, (double[3]){ 0, 0, 0 });
	key(&m, KEY_LEFTSHIFT, 1);
	button(&m, BTN_LEFT, 1);
	button(&m, BTN_RIGHT, 1); /* G's own xz plane */
	mouse_through(&m, &c, (double[3]){ 0.2, 0, 0.1 });
	/* snapped: half a turn about x, moved up; G's xz plane is the floor again, at 0.5 */
	struct xform snap;
	xform_elementary(0, 0, 1, M_PI, &snap);
	snap.p[1] = 0.5;
	manip_set(&m, &snap);
	assert_xform_same(&m.g, &snap);
	assert_int_equal(mouse_through(&m, &c, (double[3]){ 0.1, 0.5, 0.1 }), 0);
	mouse_through(&m, &c, (double[3]){ 0.4, 0.5, -0.3 });
	assert_near(m.g.p[0], 0.3, 1e-9);
	assert_near(m.g.p[1], 0.5, 1e-9);
	assert_near(m.g.p[2], -0.4, 1e-9);
	for (int i = 0; i < 9; i++)
		assert_near(m.g.r[i], snap.r[i], 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_table_3_2_every_chord),
		cmocka_unit_test(test_table_3_2_through_events),
		cmocka_unit_test(test_three_buttons_and_control_with_two_do_nothing),
		cmocka_unit_test(test_events_that_change_nothing),
		cmocka_unit_test(test_20_degree_rule_translation_along_an_axis),
		cmocka_unit_test(test_20_degree_rule_rotation),
		cmocka_unit_test(test_20_degree_rule_planar),
		cmocka_unit_test(test_refusal_repeat_and_the_camera_hook),
		cmocka_unit_test(test_line_of_sight_runs_from_the_eye_to_g),
		cmocka_unit_test(test_a_press_never_moves_g),
		cmocka_unit_test(test_linear_translation),
		cmocka_unit_test(test_planar_translation),
		cmocka_unit_test(test_rotation),
		cmocka_unit_test(test_change_of_buttons_mid_drag),
		cmocka_unit_test(test_camera_change_mid_drag),
		cmocka_unit_test(test_shift_uses_local_axes_after_a_rotation),
		cmocka_unit_test(test_alt_gives_a_tenth),
		cmocka_unit_test(test_increments),
		cmocka_unit_test(test_set_mid_drag),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
