/*
 * balance.h - balance as data (§5.4.2.1): the support polygon, the balance
 * line, the balance point and its parameters x and z (Figure 5.2), the
 * stability margin, and the rooting rules of §5.4.2.4.
 *
 * All in the floor plane, as (x, z) pairs. The human's feet (segments
 * foot_l, foot_r, toes_l, toes_r) touch the floor where their geometry
 * lies within contact_height of y = 0; the balance line joins the feet's
 * balance sites (foot_l.balance, foot_r.balance).
 */
#ifndef POSTURE_BALANCE_H
#define POSTURE_BALANCE_H

#include "figure/model.h"
#include "figure/state.h"

#define BALANCE_POLY_MAX 64
#define BALANCE_CONTACT 0.02 /* m: geometry this close to the floor bears weight */

struct balance {
	int npoly;                          /* 0 when nothing touches the floor */
	double poly[BALANCE_POLY_MAX][2];   /* support polygon, counter-clockwise seen from above */
	double ref_l[2], ref_r[2];          /* the balance line's ends: left and right foot */
	double forward[2];                  /* unit, across the balance line, the way the feet face */
	double com[3];                      /* the centre of mass balanced: the figure's, with the
					     * weights it carries (point_mass.h) */
	double point[2];                    /* the balance point: the centre of mass on the floor */
	double x;                           /* along the line: 0 at the left foot, 1 at the right */
	double z;                           /* 0 on the line, 1 at the front edge, -1 at the back */
	double margin;                      /* m to the polygon's edge: > 0 inside, < 0 outside */
	double weight_l;                    /* share of the weight on the left foot, 0..1 */
};

/*
 * Measures balance for a human figure with current frames and centre of
 * mass (kin_update). Returns 0, or -1 when the figure has no feet.
 */
int balance_measure(const struct model *m, const struct state *s, double contact_height,
		    struct balance *dest);

/*
 * The same, where the feet in the bitmask tiptoe (1 left, 2 right) may stand
 * on tiptoe: such a foot's end of the balance line moves from its balance
 * site to the ball of the foot as its heel rises off the floor, so that the
 * weight goes over what still touches it. For heels allowed to rise.
 */
int balance_measure_feet(const struct model *m, const struct state *s, double contact_height,
			 unsigned tiptoe, struct balance *dest);
/*
 * The same, balancing the centre of mass com rather than the figure's own
 * (s->com): the figure's with the weights it carries (point_mass_com).
 */
int balance_measure_com(const struct model *m, const struct state *s, double contact_height,
			unsigned tiptoe, const double com[3], struct balance *dest);
/*
 * 1 when some geom of segment seg (its bounding box, as the support polygon
 * takes it) comes within contact_height of the floor; 0 for seg < 0
 */
int balance_touches_floor(const struct model *m, const struct state *s, int seg,
			  double contact_height);

/* the parameters (x, z) of any floor point for the feet as measured in b (Figure 5.2) */
void balance_params_of(const struct balance *b, const double p[2], double *x, double *z);

/* the floor point of parameters (x, z) for the feet as measured in b (Figure 5.2 inverted) */
void balance_point_of(const struct balance *b, double x, double z, double dest[2]);

/* signed distance from p to the polygon's boundary (> 0 inside); -1e9 with no polygon */
double balance_margin(const struct balance *b, const double p[2]);

/* the support polygon of points (x, z): convex hull, counter-clockwise; returns its size */
int balance_hull(double (*pts)[2], int n, double (*dest)[2]);

enum balance_root {
	BALANCE_ROOT_LEFT_FOOT,
	BALANCE_ROOT_RIGHT_FOOT,
	BALANCE_ROOT_LOWER_TORSO,
};

/*
 * The automatic rooting rules (§5.4.2.4): through the lower torso when the
 * centre of mass is lower above the feet than 70 % of the leg's length;
 * otherwise through a foot bearing more than 60 % of the weight; otherwise
 * the current root stays (so swaying between the feet does not flip it).
 */
enum balance_root balance_choose_root(const struct balance *b, double com_height,
				      double leg_length, enum balance_root current);

#endif
