/* human_mirror.c - a human's posture left for right */
#include "figure/human_mirror.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human.h"
#include "figure/kin.h"

/* the twin of a joint named ..._l or ..._r; -1 when it has no suffix, -2 when the twin is missing */
static int
twin(const struct model *m, int j)
{
	const char *name = m->jnt_name[j];
	size_t n = strlen(name);
	if (n < 3 || name[n - 2] != '_' || (name[n - 1] != 'l' && name[n - 1] != 'r'))
		return -1;
	char other[MODEL_NAME_MAX];
	snprintf(other, sizeof other, "%.*s_%c", (int)(n - 2), name, name[n - 1] == 'l' ? 'r' : 'l');
	int t = model_find_joint(m, other);
	return t >= 0 && m->jnt_ndof[t] == m->jnt_ndof[j] ? t : -2;
}

int
human_mirror_posture(const struct model *m, struct state *s, char *err, size_t errlen)
{
	int pelvis = model_find_site(m, HUMAN_SITE_ROOT);
	if (pelvis < 0) {
		snprintf(err, errlen, "not a human figure: no %s", HUMAN_SITE_ROOT);
		return -1;
	}
	double *q = malloc(sizeof *q * (size_t)(m->ndof + 1));
	if (!q) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	memcpy(q, s->q, sizeof *q * (size_t)m->ndof);
	for (int j = 0; j < m->njnt; j++) {
		int t = twin(m, j), d0 = m->jnt_dof0[j], n = m->jnt_ndof[j];
		if (t == -2) {
			snprintf(err, errlen, "not a human figure: %s has no twin", m->jnt_name[j]);
			free(q);
			return -1;
		}
		if (t >= 0) {
			memcpy(&q[d0], &s->q[m->jnt_dof0[t]], sizeof *q * (size_t)n);
		} else if (!strncmp(m->jnt_name[j], "spine_", 6) && n == 3) {
			q[d0 + HUMAN_DOF_ABD] = -s->q[d0 + HUMAN_DOF_ABD];
			q[d0 + HUMAN_DOF_ROT] = -s->q[d0 + HUMAN_DOF_ROT];
		}
	}
	for (int d = 0; d < m->ndof; d++)
		if (q[d] < m->dof_lo[d] || q[d] > m->dof_hi[d]) {
			snprintf(err, errlen, "the mirrored posture leaves %s's limits",
				 m->jnt_name[m->dof_jnt[d]]);
			free(q);
			return -1;
		}
	/* held by the pelvis while the joints turn, then by the root it had */
	int root = s->root_site;
	kin_set_root(m, s, pelvis);
	memcpy(s->q, q, sizeof *q * (size_t)m->ndof);
	kin_update(m, s);
	kin_set_root(m, s, root);
	kin_update(m, s);
	free(q);
	return 0;
}
