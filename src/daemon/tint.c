/* tint.c - a view's humans coloured by an assessment's part scores (see tint.h) */
#include "daemon/tint.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "assess/assess_tint.h"
#include "assess/body_angles.h"
#include "daemon/assess_live.h"
#include "daemon/loads_live.h"

/*
 * Traffic-light colours, dark and saturated enough to keep their hue under
 * the renderer's shading (the lit side of a limb stays yellow, not white).
 */
const float tint_rgba[4][4] = {
	{ 0.16f, 0.66f, 0.24f, 1 }, /* green */
	{ 0.93f, 0.80f, 0.10f, 1 }, /* yellow */
	{ 0.95f, 0.47f, 0.07f, 1 }, /* orange */
	{ 0.84f, 0.11f, 0.10f, 1 }, /* red */
};
const float tint_unscored_rgba[4] = { 0.62f, 0.62f, 0.62f, 1 };

/* where a part is drawn; the arms' regions have a side */
enum tint_region {
	REGION_UPPER_ARM,
	REGION_LOWER_ARM,
	REGION_HAND,
	REGION_HEAD,
	REGION_TRUNK,
	REGION_LEGS,
	REGION_N,
};

#define ARM_REGIONS (1u << REGION_UPPER_ARM | 1u << REGION_LOWER_ARM | 1u << REGION_HAND)

/* the parts the methods score (assess.h's part names) and the regions they colour */
static const struct {
	const char *part;
	unsigned regions;
} part_regions[] = {
	{ "upper_arm", 1u << REGION_UPPER_ARM },
	{ "lower_arm", 1u << REGION_LOWER_ARM },
	{ "wrist", 1u << REGION_HAND },
	{ "wrist_twist", 1u << REGION_HAND },
	{ "neck", 1u << REGION_HEAD },
	{ "trunk", 1u << REGION_TRUNK },
	{ "legs", 1u << REGION_LEGS },
	{ "back", 1u << REGION_TRUNK }, /* OWAS */
	{ "arms", ARM_REGIONS },        /* OWAS: both arms */
};

static unsigned
regions_of(const char *part)
{
	for (size_t i = 0; i < sizeof part_regions / sizeof part_regions[0]; i++)
		if (part && !strcmp(part_regions[i].part, part))
			return part_regions[i].regions;
	return 0;
}

/* the human's segment names (figure/human.c) to regions */
static const struct {
	const char *limb; /* followed by "_l" or "_r" */
	enum tint_region region;
} limb_regions[] = {
	{ "clavicle", REGION_UPPER_ARM }, { "upperarm", REGION_UPPER_ARM },
	{ "forearm", REGION_LOWER_ARM },  { "hand", REGION_HAND },
	{ "thigh", REGION_LEGS },         { "shank", REGION_LEGS },
	{ "foot", REGION_LEGS },          { "toes", REGION_LEGS },
};

/* a vertebra's slice: L1-L5, T1-T12 */
static int
is_vertebra(const char *name)
{
	if (name[0] != 'L' && name[0] != 'T')
		return 0;
	for (const char *p = name + 1; *p; p++)
		if (!isdigit((unsigned char)*p))
			return 0;
	return name[1] != '\0';
}

static void
map_segment(const char *name, signed char *region, signed char *side)
{
	*region = -1;
	*side = -1;
	if (!strcmp(name, "pelvis") || is_vertebra(name)) {
		*region = REGION_TRUNK;
		return;
	}
	if (!strcmp(name, "head")) {
		*region = REGION_HEAD;
		return;
	}
	size_t n = strlen(name);
	if (n < 3 || name[n - 2] != '_' || (name[n - 1] != 'l' && name[n - 1] != 'r'))
		return;
	for (size_t i = 0; i < sizeof limb_regions / sizeof limb_regions[0]; i++)
		if (strlen(limb_regions[i].limb) == n - 2 && !strncmp(name, limb_regions[i].limb, n - 2)) {
			*region = (signed char)limb_regions[i].region;
			*side = (signed char)(name[n - 1] == 'l' ? BODY_LEFT : BODY_RIGHT);
			return;
		}
}

/* the limbs below each strength joint (tint=strength), by side: what its muscles hold up */
static const struct {
	const char *limb; /* followed by "_l" or "_r" */
	enum strength_joint left;
} limb_joints[] = {
	{ "hand", STRENGTH_WRIST_L },     { "forearm", STRENGTH_ELBOW_L }, { "upperarm", STRENGTH_SHOULDER_L },
	{ "thigh", STRENGTH_HIP_L },      { "shank", STRENGTH_KNEE_L },    { "foot", STRENGTH_ANKLE_L },
	{ "toes", STRENGTH_ANKLE_L },
};
_Static_assert(STRENGTH_WRIST_R == STRENGTH_WRIST_L + 1 && STRENGTH_ELBOW_R == STRENGTH_ELBOW_L + 1 &&
		       STRENGTH_SHOULDER_R == STRENGTH_SHOULDER_L + 1 && STRENGTH_HIP_R == STRENGTH_HIP_L + 1 &&
		       STRENGTH_KNEE_R == STRENGTH_KNEE_L + 1 && STRENGTH_ANKLE_R == STRENGTH_ANKLE_L + 1,
	       "a strength joint's right side follows its left");

/* the strength joint just above a human's segment, -1: none (the pelvis, clavicles, head, eyes) */
static int
joint_of(const char *name)
{
	if (is_vertebra(name)) /* the trunk above L5/S1 */
		return STRENGTH_L5S1;
	size_t n = strlen(name);
	if (n < 3 || name[n - 2] != '_' || (name[n - 1] != 'l' && name[n - 1] != 'r'))
		return -1;
	for (size_t i = 0; i < sizeof limb_joints / sizeof limb_joints[0]; i++)
		if (strlen(limb_joints[i].limb) == n - 2 && !strncmp(name, limb_joints[i].limb, n - 2))
			return (int)limb_joints[i].left + (name[n - 1] == 'r');
	return -1;
}

/* the map of m's segments, made again when the slot holds another model */
static int
map_ready(struct tint_map *map, const struct model *m, uint32_t gen)
{
	if (map->model == m && map->gen == gen)
		return map->ok ? 0 : -1;
	map->model = m;
	map->gen = gen;
	map->ok = 0;
	if (m->nseg > TINT_MAX_SEG)
		return -1;
	int trunk = 0, arms = 0;
	for (int s = 0; s < m->nseg; s++) {
		map_segment(m->seg_name[s], &map->region[s], &map->side[s]);
		map->joint[s] = (signed char)joint_of(m->seg_name[s]);
		trunk += map->region[s] == REGION_TRUNK;
		arms += map->region[s] == REGION_UPPER_ARM;
	}
	map->ok = trunk > 0 && arms > 0;
	return map->ok ? 0 : -1;
}

/* level[side][region]: the highest part-alone level of the parts drawn there (-1: none) */
static void
region_levels(const struct assess_result *const res_side[2], int level[2][REGION_N])
{
	for (int s = 0; s < 2; s++)
		for (int g = 0; g < REGION_N; g++)
			level[s][g] = -1;
	for (int s = 0; s < 2; s++) {
		const struct assess_result *r = res_side[s];
		if (!r)
			continue;
		for (int p = 0; p < r->nparts; p++) {
			unsigned regions = regions_of(r->part[p].name);
			int lv = regions ? assess_part_level(r, p) : -1;
			if (lv < 0)
				continue;
			for (int g = 0; g < REGION_N; g++) {
				if (!(regions & 1u << g))
					continue;
				/* an arm's part colours its side's arm; the others the whole body */
				int from = ARM_REGIONS & 1u << g ? s : 0, to = ARM_REGIONS & 1u << g ? s : 1;
				for (int k = from; k <= to; k++)
					if (lv > level[k][g])
						level[k][g] = lv;
			}
		}
	}
}

int
tint_segments(struct tint_map *map, const struct model *m, uint32_t gen,
	      const struct assess_result *const res_side[2], float *dest)
{
	const struct assess_result *any = res_side[0] ? res_side[0] : res_side[1];
	if (!any || map_ready(map, m, gen) < 0)
		return -1;
	int level[2][REGION_N];
	region_levels(res_side, level);
	for (int s = 0; s < m->nseg; s++) {
		const float *c = &m->seg_rgba[4 * s];
		int g = map->region[s];
		if (g >= 0) {
			int lv = level[map->side[s] < 0 ? 0 : map->side[s]][g];
			c = lv < 0 ? tint_unscored_rgba : tint_rgba[assess_level_colour(any->method, lv)];
		}
		memcpy(&dest[4 * s], c, 3 * sizeof *c);
		dest[4 * s + 3] = m->seg_rgba[4 * s + 3];
	}
	return 0;
}

/* a joint's percent capable: its weakest axis that a curve covers; NAN with none */
static double
joint_percent(const struct strength_result *sr, int j)
{
	double least = NAN;
	for (int a = 0; a < STRENGTH_NAXES; a++)
		if (!isnan(sr->percent[j][a]) && (isnan(least) || sr->percent[j][a] < least))
			least = sr->percent[j][a];
	return least;
}

int
tint_strength_segments(struct tint_map *map, const struct model *m, uint32_t gen,
		       const struct strength_result *sr, float *dest)
{
	if (map_ready(map, m, gen) < 0)
		return -1;
	for (int s = 0; s < m->nseg; s++) {
		const float *c = &m->seg_rgba[4 * s];
		if (map->joint[s] >= 0) {
			int band = strength_band(joint_percent(sr, map->joint[s]));
			c = band < 0 ? tint_unscored_rgba : tint_rgba[band];
		}
		memcpy(&dest[4 * s], c, 3 * sizeof *c);
		dest[4 * s + 3] = m->seg_rgba[4 * s + 3];
	}
	return 0;
}

/* tint=strength: the percent capable under the loads now (loads_live.h) */
static const float *
strength_figure(struct tint *t, struct daemon *d, int fig)
{
	const struct env_figure *f = &d->env.fig[fig];
	const struct loads_live_fig *live = loads_live_of(d, fig);
	if (!live || !live->valid || !live->human || !live->strength)
		return NULL;
	return tint_strength_segments(&t->map[fig], f->model, f->gen, &live->sr, t->rgba) < 0 ? NULL
												 : t->rgba;
}

const float *
tint_figure(struct tint *t, struct daemon *d, int fig, int tint)
{
	const struct env_figure *f = &d->env.fig[fig];
	if (tint <= ENV_TINT_OFF || tint >= ENV_TINT_N || !f->gen || !f->is_human)
		return NULL;
	if (tint == ENV_TINT_STRENGTH)
		return strength_figure(t, d, fig);
	const struct assess_live_fig *live = assess_live_of(d, fig);
	if (!live || !live->valid)
		return NULL;
	/* env_tint's methods follow assess_method's order after "off" */
	const struct assess_result *r = &live->res[tint - ENV_TINT_RULA];
	const struct assess_result *res_side[2] = { r, r };
	if (r->side == ASSESS_SIDE_LEFT)
		res_side[BODY_RIGHT] = NULL;
	else if (r->side == ASSESS_SIDE_RIGHT)
		res_side[BODY_LEFT] = NULL;
	return tint_segments(&t->map[fig], f->model, f->gen, res_side, t->rgba) < 0 ? NULL : t->rgba;
}

_Static_assert(ENV_TINT_REBA - ENV_TINT_RULA == ASSESS_REBA - ASSESS_RULA &&
		       ENV_TINT_OWAS - ENV_TINT_RULA == ASSESS_OWAS - ASSESS_RULA,
	       "a view's tint names an assessment method by its order");

static void
to_bytes(const float c[4], uint8_t dest[4])
{
	for (int i = 0; i < 4; i++)
		dest[i] = (uint8_t)(c[i] * 255 + 0.5f);
}

void
tint_legend(struct drawlist *dl, int tint)
{
	static const char *const names[ENV_TINT_N] = { "", "RULA", "REBA", "OWAS", "Strength" };
	/* strength_band's bands, then no curve */
	static const char *const percents[ASSESS_NCOLOURS + 1] = { ">=99", "75-99", "25-75", "<25",
								  "none" };
	static const uint8_t band[4] = { 20, 24, 32, 190 }, white[4] = { 255, 255, 255, 255 };
	if (tint <= ENV_TINT_OFF || tint >= ENV_TINT_N)
		return;
	int strength = tint == ENV_TINT_STRENGTH, ncolours = ASSESS_NCOLOURS + strength;
	enum assess_method method = (enum assess_method)(strength ? 0 : tint - ENV_TINT_RULA);
	/* one line: "RULA AL [] 1 [] 2 [] 3 [] 4", a swatch before each label */
	const int pad = 6, swatch = 12, gap = 4, sep = 10;
	char title[24];
	snprintf(title, sizeof title, "%s %s", names[tint], strength ? "%" : assess_level_word(method));
	int w = pad + (int)strlen(title) * VIEW_CHAR_PX;
	for (int c = 0; c < ncolours; c++)
		w += sep + swatch + gap +
		     (int)strlen(strength ? percents[c] : assess_colour_levels(method, (enum assess_colour)c)) *
			     VIEW_CHAR_PX;
	w += pad;
	double top = 4, left = 4, base = top + VIEW_LINE_PX - 5;
	view_add_rect(dl, left, top, left + w, top + VIEW_LINE_PX, band);
	view_add_text(dl, left + pad, base, title, white, VIEW_ALIGN_LEFT);
	double x = left + pad + (double)strlen(title) * VIEW_CHAR_PX;
	for (int c = 0; c < ncolours; c++) {
		const char *levels = strength ? percents[c] : assess_colour_levels(method, (enum assess_colour)c);
		uint8_t rgba[4];
		to_bytes(c < ASSESS_NCOLOURS ? tint_rgba[c] : tint_unscored_rgba, rgba);
		x += sep;
		double sy = top + (VIEW_LINE_PX - swatch) / 2.0;
		view_add_rect(dl, x, sy, x + swatch, sy + swatch, rgba);
		x += swatch + gap;
		view_add_text(dl, x, base, levels, white, VIEW_ALIGN_LEFT);
		x += (double)strlen(levels) * VIEW_CHAR_PX;
	}
}
