/*
 * fit_touch.c - the human's pairs that touch in a normal posture.
 *
 * Measured with the self-clearance of the standard human (1.75 m, 75 kg)
 * at rest standing and seated as the driver of the vehicle seat (the demo
 * scenes), jointed pairs left out: every pair below met or overlapped
 * there, by up to 3.2 cm, or (the thighs) came within 3 mm.
 *
 *   trunk x trunk       the pelvis, the 17 slices L5 .. T1 and the head are one
 *                       flexible trunk drawn as slices whose meshes overlap
 *                       their neighbours' by design (up to 2.9 cm, slices four
 *                       apart); a chin on the chest is among them and is not
 *                       reported
 *   clavicle x thorax   the clavicle lies on the upper thorax and under the
 *   clavicle x head     head's lower part (T1 .. T6, the head: up to 3.2 cm)
 *   thigh x L5, L4, L3  the thigh's top meets the lumbar slices above the hip,
 *                       more so seated (1.4 cm)
 *   thigh_l x thigh_r   the inner thighs: 3 mm standing at rest; they touch on
 *                       heavier manikins
 *   clavicle x clavicle their medial ends meet at the sternum (1.4 cm at rest)
 */
#include "fit/fit_touch.h"

#include <stdlib.h>
#include <string.h>

enum part { OTHER, TRUNK_LUMBAR_LOW, TRUNK, CLAVICLE, THIGH };

/* L5, L4, L3: the slices a thigh meets */
static int
lumbar_low(const char *n)
{
	return n[0] == 'L' && (n[1] == '3' || n[1] == '4' || n[1] == '5') && n[2] == 0;
}

static int
slice(const char *n)
{
	if ((n[0] != 'L' && n[0] != 'T') || n[1] < '1' || n[1] > '9')
		return 0;
	char *end;
	long k = strtol(n + 1, &end, 10);
	return *end == 0 && k >= 1 && k <= (n[0] == 'L' ? 5 : 12);
}

static enum part
part_of(const char *n)
{
	if (lumbar_low(n))
		return TRUNK_LUMBAR_LOW;
	if (slice(n) || !strcmp(n, "pelvis") || !strcmp(n, "head"))
		return TRUNK;
	if (!strcmp(n, "clavicle_l") || !strcmp(n, "clavicle_r"))
		return CLAVICLE;
	if (!strcmp(n, "thigh_l") || !strcmp(n, "thigh_r"))
		return THIGH;
	return OTHER;
}

static int
is_human(const struct model *m)
{
	return model_find_segment(m, "pelvis") >= 0 && model_find_segment(m, "T1") >= 0 &&
	       model_find_segment(m, "thigh_l") >= 0 && model_find_segment(m, "clavicle_r") >= 0;
}

int
fit_touch(const struct model *m, int a, int b)
{
	if (a < 0 || b < 0 || a >= m->nseg || b >= m->nseg || !is_human(m))
		return 0;
	enum part pa = part_of(m->seg_name[a]), pb = part_of(m->seg_name[b]);
	if (pa > pb) {
		enum part t = pa;
		pa = pb;
		pb = t;
	}
	int trunk_a = pa == TRUNK || pa == TRUNK_LUMBAR_LOW;
	int trunk_b = pb == TRUNK || pb == TRUNK_LUMBAR_LOW;
	if (trunk_a && trunk_b)
		return 1;
	if ((trunk_a || pa == CLAVICLE) && pb == CLAVICLE)
		return 1;
	if (pa == TRUNK_LUMBAR_LOW && pb == THIGH)
		return 1;
	if (pa == THIGH && pb == THIGH)
		return 1;
	return 0;
}
