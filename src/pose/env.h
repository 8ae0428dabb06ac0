/*
 * env.h - the environment (§A.3): the figures the daemon holds, their
 * constraints, and the ids clients use for them.
 *
 * Ids carry a generation (Box2D's b2BodyId): a slot reused by a later
 * figure or constraint has a new generation, so an old id is refused as
 * stale rather than silently naming something else.
 */
#ifndef POSTURE_ENV_H
#define POSTURE_ENV_H

#include <stdint.h>

#include "pose/behave.h"
#include "figure/human.h"
#include "figure/population.h"
#include "pose/ik.h"
#include "pose/load.h"
#include "figure/model.h"
#include "figure/state.h"

#define ENV_MAX_FIGURES 40 /* a family of both sexes, 1 + 16 each, and a few more */
#define ENV_MAX_CONSTRAINTS 64
#define ENV_MAX_LOADS 64
#define ENV_LOAD_FORCE_MAX 1e5  /* N: a load's force at most (10 tonnes' weight; a body gives way far below) */
#define ENV_LOAD_TORQUE_MAX 1e4 /* N m: a load's torque at most */
#define ENV_LOAD_MASS_MAX 1000.0 /* kg: a weight at most (the assessments' load limit too) */
#define ENV_PATH_MAX 256
#define ENV_MAX_VIEWS 8
#define ENV_VIEW_FOVY_DEG 40.0 /* a view's vertical field of view unless it asks for another */
#define ENV_VIEW_FOVY_MIN 1.0  /* the fields of view a view may ask for, degrees */
#define ENV_VIEW_FOVY_MAX 170.0
#define ENV_VIEW_CONES 4       /* the cones an eye view's picture marks at most */

enum env_err {
	ENV_OK = 0,
	ENV_NOT_FOUND = -1,
	ENV_STALE = -2,
	ENV_EXISTS = -3,
	ENV_FULL = -4,
	ENV_BAD = -5,
};

/*
 * A manikin: a human whose measures came from a population (load human
 * with measures, a percentile or a population; load family). Its body is
 * its human_def's measures alone; this says where they came from.
 */
struct env_manikin {
	char population[MODEL_NAME_MAX]; /* "": not a manikin of a population */
	unsigned char given[POPULATION_NCOL]; /* 1: a column it was conditioned on (ANSUR II's order) */
	double percentile;  /* the stature percentile it was made at; NAN: none */
	double mahalanobis; /* the distance of its given measures from the population's mean */
	char family[MODEL_NAME_MAX]; /* the family it is one of ("": none), its prefix */
	int member;         /* its number in the family: 0 the centre */
	double coverage;    /* the family's coverage, 0 to 1 (NAN: not one of a family) */
};

struct env_figure {
	uint32_t gen; /* 0: a free slot */
	char name[MODEL_NAME_MAX];
	/* where the model came from, so a session can rebuild it */
	int is_human;
	struct human_def human;
	struct env_manikin manikin; /* a human made from a population: how */
	char path[ENV_PATH_MAX]; /* figure file, relative to the state directory */
	struct model *model;
	struct state *state;
	struct ik *ik;
	int ik_stale; /* the constraint set changed since the solver was filled */
	struct behave *behave; /* the human's behaviours when switched on, else NULL */
};

struct env_constraint {
	uint32_t gen; /* 0: a free slot */
	char name[MODEL_NAME_MAX];
	int fig; /* figure slot; the def's site and joint indices are that figure's */
	int transient; /* a mode's own (a drag's): not part of a session, gone with the mode */
	struct ik_constraint_def def;
};

/*
 * An external load on a figure (add load): a force and a torque in the
 * world frame at one of its sites, or a weight (a mass hanging there, its
 * force mass x LOAD_GRAVITY down). What the figure feels this frame,
 * with what its hands carry, is load_set.h's.
 */
struct env_load {
	uint32_t gen; /* 0: a free slot */
	char name[MODEL_NAME_MAX];
	int fig;          /* figure slot */
	int site;         /* the site it acts at; its segment carries it */
	double force[3];  /* N, world frame (y up); a weight's: (0, -mass g, 0) */
	double torque[3]; /* N m, world frame; a weight's: 0 */
	double mass;      /* kg: a weight; 0: a force */
};

/*
 * A limb of a behaving human held to another figure (Table D.4, §D.1.1):
 * ATTACH_GRAB, the hand grabbed the object, which follows the hand (rel:
 * the object's base segment in the palm's frame); ATTACH_LOCAL, the hand
 * or foot holds a location local to the object's segment and follows it
 * (rel: the palm or toes in that segment's frame). See attach.h.
 */
enum attach_kind { ATTACH_GRAB, ATTACH_LOCAL };
enum attach_limb { ATTACH_HAND, ATTACH_FOOT };

struct env_attach {
	int used;
	enum attach_kind kind;
	enum attach_limb limb;
	int fig, side;  /* the human and its limb */
	int obj, seg;   /* the object figure and its segment */
	struct xform rel;
};

#define ENV_MAX_ATTACH (4 * ENV_MAX_FIGURES)

/*
 * A family shown at the kiosk (show family): its members in a row or
 * overlaid, the selected one opaque and the others translucent ghosts. A
 * display state, kept in sessions, undo and the journal with the roots the
 * arrangement set, so what comes back draws and picks as it was left.
 * Members and the selected one are looked up by name when needed: a
 * member unloaded leaves the others shown, the selected one gone falls
 * back to the first member.
 */
enum env_arrange {
	ENV_SHOW_OFF,
	ENV_SHOW_ROW,     /* side by side along a view's horizontal */
	ENV_SHOW_OVERLAY, /* all at the selected one's place; the others ghosts */
};

struct env_show {
	int arrange;                   /* enum env_arrange */
	char family[MODEL_NAME_MAX];   /* the family's prefix */
	char selected[MODEL_NAME_MAX]; /* the member drawn opaque, the status line's */
	double spacing;                /* ENV_SHOW_ROW: metres between neighbours' places */
};

/*
 * What a view's tint colours the humans' body parts by: nothing (their own
 * colours), a posture assessment's part scores, or the percent of the
 * population strong enough at each joint under the loads (the daemon's
 * analyses; this layer only keeps the choice).
 */
enum env_tint {
	ENV_TINT_OFF,
	ENV_TINT_RULA,
	ENV_TINT_REBA,
	ENV_TINT_OWAS,
	ENV_TINT_STRENGTH,
	ENV_TINT_N,
};

/* which eye a view through a manikin's eyes looks from (eyeview.h) */
enum env_eyes {
	ENV_EYES_BOTH,  /* the cyclopean eye, midway between the two */
	ENV_EYES_LEFT,
	ENV_EYES_RIGHT,
};

/* a named view (§1.7: several graphics windows), its camera aimed at a point */
struct env_view {
	int used;
	char name[MODEL_NAME_MAX];
	int width, height;
	double eye[3], target[3];
	double fovy_deg; /* vertical field of view, degrees, kept as given so it reads back exactly */
	int icons; /* 1: the manipulation icons, balance and goals */
	int tint;  /* enum env_tint: the humans' parts coloured by an assessment's part scores */
	int loads_hidden; /* 1: the loads' arrows not drawn (set view VIEW loads=off); 0 drawn */
	/* a view through a figure's eyes (eyeview.h): eye, target and fovy_deg follow them */
	char eyes[MODEL_NAME_MAX]; /* the figure's name; "": a camera of its own */
	int eyes_which;            /* enum env_eyes */
	double hfov_deg;           /* horizontal field of view, degrees, kept as given */
	double cones_deg[ENV_VIEW_CONES]; /* an eye view's marked cones: full angles, degrees */
	int ncones;                /* how many are marked; 0: none */
	/* manikins' lines of sight drawn as cones from their eyes (eyeview.h): "" none,
	 * "all" every figure with eyes, else a figure's name */
	char sight[MODEL_NAME_MAX];
	double sight_len; /* m: the cones' sides, from the eye to the rim (set while sight is) */
};

struct env {
	struct env_figure fig[ENV_MAX_FIGURES];
	struct env_constraint con[ENV_MAX_CONSTRAINTS];
	struct env_load load[ENV_MAX_LOADS];
	struct env_view view[ENV_MAX_VIEWS];
	/* the kiosk's screen: the views tiled on it, in order (slots); 0: the first view alone */
	int layout[ENV_MAX_VIEWS];
	int nlayout;
	struct env_attach att[ENV_MAX_ATTACH];
	struct env_show show;
	uint32_t next_gen;
};

void env_init(struct env *e);
/* frees every figure; the env is empty and usable afterwards */
void env_clear(struct env *e);

/*
 * Adds a figure, taking ownership of model (freed on failure too).
 * name NULL picks one from the model's. Returns the slot or an env_err.
 */
int env_add_figure(struct env *e, struct model *model, const char *name, int is_human,
		   const struct human_def *human, const char *path);
/* removes a figure, its constraints, its loads and what held it or it held */
void env_remove_figure(struct env *e, int slot);

/* ref is a name or an id "f<slot>.<gen>"; returns the slot or an env_err */
int env_find_figure(const struct env *e, const char *ref);
int env_find_constraint(const struct env *e, const char *ref);
/* a load by name or id "l<slot>.<gen>": the slot or an env_err */
int env_find_load(const struct env *e, const char *ref);

/* writes the id of a slot ("f3.12", "c0.7") into dest */
void env_figure_id(const struct env *e, int slot, char dest[32]);
void env_constraint_id(const struct env *e, int slot, char dest[32]);
void env_load_id(const struct env *e, int slot, char dest[32]);

/* adds a constraint (name NULL: c1, c2, ...); returns the slot or an env_err */
int env_add_constraint(struct env *e, int fig, const char *name,
		       const struct ik_constraint_def *def);
void env_remove_constraint(struct env *e, int slot);
/* replaces a constraint's definition (goal moves, switching on and off) */
void env_set_constraint(struct env *e, int slot, const struct ik_constraint_def *def);

/*
 * Adds a load (name NULL: l1, l2, ...): def's fig, site, force, torque and
 * mass, checked (a figure there, a site of it, finite values, a weight's
 * force its mass's). Returns the slot, or ENV_EXISTS (the name is taken),
 * ENV_FULL, ENV_BAD (def is not a load of this environment).
 */
int env_add_load(struct env *e, const char *name, const struct env_load *def);
void env_remove_load(struct env *e, int slot);

/* refills a figure's solver from its constraints when they changed */
void env_sync_solver(struct env *e, int fig);

/* the constraint's index in its figure's solver, or -1 (disabled or not yet synced) */
int env_solver_index(const struct env *e, int slot);

/* a view by name, or -1 */
int env_find_view(const struct env *e, const char *name);
/* a tint's name ("off", "rula", "reba", "owas", "strength"; "?" out of range), and back (-1: none such) */
const char *env_tint_str(int tint);
int env_tint_find(const char *name);

/*
 * Moves site `site` of figure fig to loc (its segment's frame), marking it
 * moved (model_set_site), the figure updated. The root site is where the
 * figure is held: its segment stays put and the root's global frame moves
 * with the site, rather than the whole figure moving under it.
 */
void env_place_site(struct env *e, int fig, int site, const struct xform *loc);

/* number of figures */
int env_count(const struct env *e);

#endif
