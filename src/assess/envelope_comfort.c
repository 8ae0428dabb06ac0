/*
 * envelope_comfort.c - the comfort zone's joint ranges (envelope.h): the
 * defaults with their sources, a parser of "JOINT.DOF=LO,HI;..." for
 * requests, and the narrowed limits a comfort solve runs with.
 *
 * The dofs are the human's (figure/human_data.c): limb joints in ISB order,
 * flexion first (Wu et al. 2005); the right side mirrors the left with the
 * same signs, so one range serves both hands. "spine" is the whole thoracic
 * and lumbar spine (spine_0 .. spine_16): its range is the trunk's, shared
 * out over the vertebrae in proportion to each one's own limit on that side
 * (White and Panjabi's table, as the limits are), so every vertebra stays
 * within its share and the trunk within the range.
 */
#include "assess/envelope_comfort.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human_data.h"

static const struct {
	struct envelope_comfort_range r;
	const char *source;
} defaults[] = {
	{ { "clavicle", 1, -10, 0 },
	  "RULA (McAtamney & Corlett 1993, Applied Ergonomics 24:91-99): a raised shoulder adds "
	  "a point to the upper arm; the clavicle's elevation held at or below rest" },
	{ { "shoulder", 0, -20, 20 },
	  "RULA upper arm score 1: 20 degrees extension to 20 degrees flexion; ISO 11226 / "
	  "EN 1005-4 (as in DELMIA's Fault Monitor): upper-arm elevation 0-20 degrees acceptable" },
	{ { "shoulder", 1, 0, 20 },
	  "ISO 11226 / EN 1005-4 (as in DELMIA's Fault Monitor): upper-arm elevation 0-20 "
	  "degrees acceptable; RULA adds a point when the upper arm is abducted" },
	{ { "elbow", 0, 60, 100 }, "RULA lower arm score 1: 60-100 degrees flexion" },
	{ { "wrist", 0, -15, 15 },
	  "RULA wrist: within 15 degrees of flexion or extension (score 2; 3 beyond)" },
	{ { "wrist", 1, 0, 0 },
	  "RULA wrist: bent from the midline (radial or ulnar deviation) adds a point; held "
	  "neutral" },
	{ { "wrist", 2, -40, 40 },
	  "RULA wrist twist score 1: mainly in mid-range (taken as the middle half of the "
	  "forearm's 80 degrees each way)" },
	{ { "spine", 0, 0, 20 },
	  "RULA trunk: 0-20 degrees flexion (score 2; upright alone scores 1); no extension" },
	{ { "spine", 1, -10, 10 },
	  "ISO 11226 / EN 1005-4 (as in DELMIA's Fault Monitor): trunk side-bending of 10 "
	  "degrees or more is at best conditionally acceptable" },
	{ { "spine", 2, -10, 10 },
	  "ISO 11226 / EN 1005-4 (as in DELMIA's Fault Monitor): trunk twist of 10 degrees or "
	  "more is at best conditionally acceptable" },
};
#define NDEFAULT ((int)(sizeof defaults / sizeof defaults[0]))

void
envelope_comfort_default(struct envelope_comfort *dest)
{
	memset(dest, 0, sizeof *dest);
	for (int i = 0; i < NDEFAULT; i++)
		dest->r[dest->n++] = defaults[i].r;
}

const char *
envelope_comfort_source(int i)
{
	return i >= 0 && i < NDEFAULT ? defaults[i].source : NULL;
}

/* the range of joint.dof in c, or NULL */
static struct envelope_comfort_range *
find_range(struct envelope_comfort *c, const char *joint, int dof)
{
	for (int i = 0; i < c->n; i++)
		if (c->r[i].dof == dof && !strcmp(c->r[i].joint, joint))
			return &c->r[i];
	return NULL;
}

static const char *
skip_space(const char *p)
{
	while (isspace((unsigned char)*p))
		p++;
	return p;
}

static int
parse_number(const char **pp, double *dest)
{
	char *end;
	errno = 0;
	*dest = strtod(*pp, &end);
	if (end == *pp || errno || !isfinite(*dest))
		return -1;
	*pp = skip_space(end);
	return 0;
}

int
envelope_comfort_parse(const char *text, struct envelope_comfort *dest, char *err, size_t errlen)
{
	struct envelope_comfort c = *dest;
	const char *p = skip_space(text);
	while (*p) {
		char joint[sizeof c.r[0].joint];
		size_t n = 0;
		while (isalnum((unsigned char)p[n]) || p[n] == '_')
			n++;
		if (!n || n >= sizeof joint || p[n] != '.') {
			snprintf(err, errlen, "comfort: expected JOINT.DOF=LO,HI at \"%.20s\"", p);
			return -1;
		}
		memcpy(joint, p, n);
		joint[n] = 0;
		p += n + 1;
		char *end;
		long dof = strtol(p, &end, 10);
		if (end == p || dof < 0 || dof >= 6) {
			snprintf(err, errlen, "comfort: %s: the dof is an index 0..5", joint);
			return -1;
		}
		p = skip_space(end);
		double lo, hi;
		if (*p != '=' || (p = skip_space(p + 1), parse_number(&p, &lo) < 0) || *p != ',' ||
		    (p = skip_space(p + 1), parse_number(&p, &hi) < 0)) {
			snprintf(err, errlen, "comfort: %s.%ld: expected =LO,HI in degrees", joint, dof);
			return -1;
		}
		if (lo > hi || fabs(lo) > 360 || fabs(hi) > 360) {
			snprintf(err, errlen, "comfort: %s.%ld: %g,%g is not a range of degrees", joint,
				 dof, lo, hi);
			return -1;
		}
		struct envelope_comfort_range *r = find_range(&c, joint, (int)dof);
		if (!r) {
			if (c.n == ENVELOPE_COMFORT_MAX) {
				snprintf(err, errlen, "comfort: more than %d ranges", ENVELOPE_COMFORT_MAX);
				return -1;
			}
			r = &c.r[c.n++];
			memcpy(r->joint, joint, n + 1);
			r->dof = (int)dof;
		}
		r->lo = lo;
		r->hi = hi;
		if (*p == ';')
			p = skip_space(p + 1);
		else if (*p) {
			snprintf(err, errlen, "comfort: expected ';' at \"%.20s\"", p);
			return -1;
		}
	}
	*dest = c;
	return 0;
}

/* narrows dof d of m to [lo, hi] radians within its limits; -1 when they do not meet */
static int
narrow(struct model *m, int d, double lo, double hi)
{
	double a = fmax(m->dof_lo[d], lo), b = fmin(m->dof_hi[d], hi);
	if (a > b)
		return -1;
	m->dof_lo[d] = a;
	m->dof_hi[d] = b;
	return 0;
}

int
envelope_comfort_apply(const struct envelope_comfort *c, struct model *m, int side, char *err,
		       size_t errlen)
{
	const double rad = M_PI / 180;
	for (int i = 0; i < c->n; i++) {
		const struct envelope_comfort_range *r = &c->r[i];
		int bad = 0;
		if (!strcmp(r->joint, "spine")) {
			/* the trunk's range shared out by each vertebra's limit on that side */
			double sum_lo = 0, sum_hi = 0;
			int js[HUMAN_NSLICE];
			for (int k = 0; k < HUMAN_NSLICE; k++) {
				char name[24];
				snprintf(name, sizeof name, "spine_%d", k);
				js[k] = model_find_joint(m, name);
				if (js[k] < 0 || r->dof >= m->jnt_ndof[js[k]]) {
					snprintf(err, errlen, "comfort: the figure has no spine.%d", r->dof);
					return -1;
				}
				int d = m->jnt_dof0[js[k]] + r->dof;
				sum_lo += m->dof_lo[d];
				sum_hi += m->dof_hi[d];
			}
			for (int k = 0; k < HUMAN_NSLICE && !bad; k++) {
				int d = m->jnt_dof0[js[k]] + r->dof;
				double lo = sum_lo < 0 ? r->lo * rad * m->dof_lo[d] / sum_lo : 0;
				double hi = sum_hi > 0 ? r->hi * rad * m->dof_hi[d] / sum_hi : 0;
				/* a range on one side of zero only */
				if (r->lo > 0)
					lo = sum_hi > 0 ? r->lo * rad * m->dof_hi[d] / sum_hi : 0;
				if (r->hi < 0)
					hi = sum_lo < 0 ? r->hi * rad * m->dof_lo[d] / sum_lo : 0;
				bad = narrow(m, d, lo, hi) < 0;
			}
		} else {
			char name[40];
			snprintf(name, sizeof name, "%s%s", r->joint, human_side_sfx[side ? 1 : 0]);
			int j = model_find_joint(m, name);
			if (j < 0)
				j = model_find_joint(m, r->joint);
			if (j < 0 || r->dof >= m->jnt_ndof[j]) {
				snprintf(err, errlen, "comfort: the figure has no joint dof %s.%d", r->joint,
					 r->dof);
				return -1;
			}
			bad = narrow(m, m->jnt_dof0[j] + r->dof, r->lo * rad, r->hi * rad) < 0;
		}
		if (bad) {
			snprintf(err, errlen, "comfort: %s.%d %g,%g lies outside the joint's limits",
				 r->joint, r->dof, r->lo, r->hi);
			return -1;
		}
	}
	return 0;
}
