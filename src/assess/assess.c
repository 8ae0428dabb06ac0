/*
 * assess.c - the thresholds the methods' texts leave open (each default
 * with where it comes from), and the writing of a derivation the three
 * scorers share.
 *
 * The methods are observational: RULA, REBA and OWAS say "shoulder raised",
 * "twisted", "out to the side" and leave the degrees to the observer. Where
 * open implementations chose a number, the source names it (research:
 * human-factors §1.5, §2.4); where we chose, it says "chosen" and what
 * others did.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "assess/assess.h"
#include "assess/assess_internal.h"

struct assess_config
assess_config_default(void)
{
	return (struct assess_config){
		.upright = 5,
		.shoulder_raised = 10,
		.arm_abducted = 35,
		.arm_rotated = 45,
		.trunk_twist = 15,
		.trunk_side_bend = 10,
		.neck_twist = 15,
		.neck_side_bend = 8,
		.wrist_neutral = 5,
		.wrist_deviated = 10,
		.wrist_twist_end = 0.75,
		.across_midline = 0,
		.out_to_side = 0.10,
		.uneven_weight = 0.2,
		.knee_bent = 30,
		.owas_back = 20,
		.kneel_height = 0.10,
	};
}

#define KEY(name, unit, lo, hi, src) { #name, offsetof(struct assess_config, name), unit, lo, hi, src }

const struct assess_config_key assess_config_keys[] = {
	KEY(upright, "deg", 0, 30,
	    "chosen: 5; cf. ignc-research/ergonomic_assessment (trunk score 1 at <= 7 deg), "
	    "rs9000/ergonomics (REBA trunk band 1 only 0-1 deg)"),
	KEY(shoulder_raised, "deg", 0, 45,
	    "chosen: 10; cf. ignc-research (head-neck vs neck-shoulder <= 105 deg, about 15 deg "
	    "of elevation), rs9000/ergonomics (shoulder 2 cm above the neck)"),
	KEY(arm_abducted, "deg", 0, 90,
	    "ignc-research (shoulder line vs upper arm >= 125 deg, about 35 deg); "
	    "rs9000/ergonomics 45 deg"),
	KEY(arm_rotated, "deg", 0, 90,
	    "chosen: 45, half the shoulder's internal rotation; no open implementation measures it"),
	KEY(trunk_twist, "deg", 0, 60, "ignc-research (hip line vs shoulder line > 15 deg)"),
	KEY(trunk_side_bend, "deg", 0, 60,
	    "chosen: 10; cf. DELMIA Fault Monitor (>= 10 deg, after ISO 11226), ignc-research "
	    "(outside 87-93 deg, i.e. 3), rs9000/ergonomics 30 deg"),
	KEY(neck_twist, "deg", 0, 60, "ignc-research (nose-neck vs shoulder line outside 75-105 deg)"),
	KEY(neck_side_bend, "deg", 0, 60,
	    "ignc-research (outside 82-98 deg, i.e. 8); rs9000/ergonomics 20 deg"),
	KEY(wrist_neutral, "deg", 0, 15,
	    "chosen: 5 (the RULA worksheets draw neutral at 0 deg; ignc-research scores the "
	    "wrist 1 always)"),
	KEY(wrist_deviated, "deg", 0, 30,
	    "chosen: 10, a third of the ulnar deviation range; no open implementation measures it"),
	KEY(wrist_twist_end, "fraction", 0, 1,
	    "chosen: 0.75, the outer quarter of pronation or supination; rs9000/ergonomics flags "
	    "a hand turned > 30 deg"),
	KEY(across_midline, "m", 0, 0.3,
	    "chosen: 0, any crossing of the midsagittal plane (RULA: 'working across the "
	    "midline'); no open implementation measures it"),
	KEY(out_to_side, "m", 0, 0.5,
	    "chosen: 0.10; cf. ignc-research (shoulder line vs forearm > 100 deg)"),
	KEY(uneven_weight, "fraction", 0, 1,
	    "chosen: 0.2 (a 60/40 split); cf. ignc-research (legs 2 when the knees differ by "
	    "> 15 deg)"),
	KEY(knee_bent, "deg", 0, 150,
	    "chosen: 30, REBA's first knee band; cf. rs9000/ergonomics OWAS (knee angle < 95 deg, "
	    "85 of flexion)"),
	KEY(owas_back, "deg", 0, 90,
	    "OWAS training slides (scribd 630537767: straight < 20, bent > 20 deg); "
	    "rs9000/ergonomics 20 (bent), 30 (side)"),
	KEY(kneel_height, "m", 0, 0.5,
	    "chosen: 0.10; cf. rs9000/ergonomics (kneeling: knee within 0.1 m of the ankle's "
	    "height)"),
};
const size_t assess_config_nkeys = sizeof assess_config_keys / sizeof assess_config_keys[0];

int
assess_config_set(struct assess_config *cfg, const char *key, double value, char *err,
		  size_t errlen)
{
	for (size_t i = 0; i < assess_config_nkeys; i++) {
		const struct assess_config_key *k = &assess_config_keys[i];
		if (strcmp(k->key, key))
			continue;
		/* NaN fails both comparisons: refused with the range */
		if (!(value >= k->min && value <= k->max)) {
			snprintf(err, errlen, "%s=%g is outside %g..%g %s", key, value, k->min, k->max,
				 k->unit);
			return -1;
		}
		*(double *)((char *)cfg + k->offset) = value;
		return 0;
	}
	snprintf(err, errlen, "unknown assessment threshold '%s'", key);
	return -1;
}

void
assess_begin(struct assess_result *r, enum assess_method m, int side)
{
	r->method = m;
	r->side = side;
	r->score = 0;
	r->action_level = 0;
	r->action = "";
	r->nparts = 0;
	r->nlookups = 0;
	r->worst = -1;
	r->code[0] = 0;
}

struct assess_part *
assess_part(struct assess_result *r, const char *name, const char *angle_name, double angle,
	    int body, int max)
{
	/* the scorers add a fixed number of parts, below ASSESS_MAX_PARTS */
	struct assess_part *p = &r->part[r->nparts++];
	p->name = name;
	p->angle_name = angle_name;
	p->angle = angle;
	p->base = 0;
	p->band[0] = 0;
	p->nadj = 0;
	p->score = 0;
	p->max = max;
	p->body = body;
	return p;
}

void
assess_band(struct assess_part *p, int base, const char *band)
{
	size_t n = strlen(band);
	if (n >= sizeof p->band)
		n = sizeof p->band - 1;
	memcpy(p->band, band, n);
	p->band[n] = 0;
	p->base = base;
}

/*
 * The reasons' formatting, without vsnprintf (a frame formats a dozen of
 * them; the printf family cost more than the scoring): %s, %d, %.1f, %.2f
 * and %g, where %g prints a threshold as set (at most 4 decimals, trailing
 * zeros dropped). Writes at most end - o - 1 characters and a NUL.
 */
static char *
put_char(char *o, char *end, char c)
{
	if (o < end - 1)
		*o++ = c;
	return o;
}

static char *
put_str(char *o, char *end, const char *s)
{
	while (*s && o < end - 1)
		*o++ = *s++;
	return o;
}

static char *
put_uint(char *o, char *end, unsigned long long v)
{
	char d[24];
	int n = 0;
	do
		d[n++] = (char)('0' + v % 10);
	while ((v /= 10) && n < 24);
	while (n)
		o = put_char(o, end, d[--n]);
	return o;
}

/* x with decimals places (round half to even, as printf on exact halves); trim drops trailing zeros */
static char *
put_fixed(char *o, char *end, double x, int decimals, int trim)
{
	if (isnan(x))
		return put_str(o, end, "nan");
	if (x < 0) {
		o = put_char(o, end, '-');
		x = -x;
	}
	if (x >= 1e15)
		return put_str(o, end, "inf");
	double scale = 1;
	for (int i = 0; i < decimals; i++)
		scale *= 10;
	unsigned long long v = (unsigned long long)nearbyint(x * scale), unit = (unsigned long long)scale;
	o = put_uint(o, end, v / unit);
	unsigned long long frac = v % unit;
	if (!decimals || (trim && !frac))
		return o;
	o = put_char(o, end, '.');
	for (unsigned long long d = unit / 10; d; d /= 10) {
		o = put_char(o, end, (char)('0' + frac / d % 10));
		if (trim && !(frac % d))
			break;
	}
	return o;
}

static void
format_reason(char *o, size_t size, const char *fmt, va_list ap)
{
	char *end = o + size;
	for (const char *f = fmt; *f; f++) {
		if (*f != '%') {
			o = put_char(o, end, *f);
		} else if (!strncmp(f, "%s", 2)) {
			o = put_str(o, end, va_arg(ap, const char *));
			f += 1;
		} else if (!strncmp(f, "%d", 2)) {
			int v = va_arg(ap, int);
			if (v < 0)
				o = put_char(o, end, '-');
			o = put_uint(o, end, v < 0 ? -(unsigned long long)v : (unsigned long long)v);
			f += 1;
		} else if (!strncmp(f, "%.1f", 4) || !strncmp(f, "%.2f", 4)) {
			o = put_fixed(o, end, va_arg(ap, double), f[2] - '0', 0);
			f += 3;
		} else if (!strncmp(f, "%g", 2)) {
			o = put_fixed(o, end, va_arg(ap, double), 4, 1);
			f += 1;
		} else {
			o = put_char(o, end, '%'); /* the scorers use no other conversion */
		}
	}
	*o = 0;
}

void
assess_adjust(struct assess_part *p, int value, const char *fmt, ...)
{
	if (p->nadj >= ASSESS_MAX_ADJ)
		return;
	struct assess_adjust *a = &p->adj[p->nadj++];
	a->value = value;
	va_list ap;
	va_start(ap, fmt);
	format_reason(a->reason, sizeof a->reason, fmt, ap);
	va_end(ap);
}

int
assess_close(struct assess_part *p, int lo, int hi)
{
	int s = p->base;
	for (int i = 0; i < p->nadj; i++)
		s += p->adj[i].value;
	p->score = s < lo ? lo : s > hi ? hi : s;
	return p->score;
}

int
assess_lookup(struct assess_result *r, const char *table, int nidx, const char *const *names,
	      const int *idx, int value)
{
	struct assess_lookup *l = &r->lookup[r->nlookups++];
	l->table = table;
	l->nidx = nidx;
	for (int i = 0; i < nidx; i++) {
		l->idx_name[i] = names[i];
		l->idx[i] = idx[i];
	}
	l->value = value;
	return value;
}

void
assess_set_worst(struct assess_result *r)
{
	double best = -1;
	r->worst = -1;
	for (int i = 0; i < r->nparts; i++) {
		const struct assess_part *p = &r->part[i];
		if (!p->body || p->max <= 1)
			continue;
		double rel = (double)(p->score - 1) / (p->max - 1);
		if (rel > best) {
			best = rel;
			r->worst = i;
		}
	}
}

int
assess_upper_arm_band(double f, const char **band)
{
	if (f <= -20) {
		*band = "more than 20 deg extension";
		return 2;
	}
	if (f < 20) {
		*band = "20 deg extension to 20 deg flexion";
		return 1;
	}
	if (f < 45) {
		*band = "20-45 deg flexion";
		return 2;
	}
	if (f < 90) {
		*band = "45-90 deg flexion";
		return 3;
	}
	*band = "90 deg flexion or more";
	return 4;
}

int
assess_lower_arm_band(double e, const char **band)
{
	if (e > 60 && e < 100) {
		*band = "60-100 deg flexion";
		return 1;
	}
	*band = e <= 60 ? "60 deg flexion or less" : "100 deg flexion or more";
	return 2;
}
