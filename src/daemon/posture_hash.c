/* posture_hash.c - postures as numbers: the journal's, the recordings', `status`'s */
#include "daemon/posture_hash.h"

#include "pose/behave.h"

uint64_t
posture_fnv(uint64_t h, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t i = 0; i < n; i++)
		h = (h ^ b[i]) * 1099511628211ull;
	return h;
}

uint64_t
posture_figure_hash(const struct env_figure *f)
{
	uint64_t h = state_hash(f->model, f->state);
	if (!f->behave)
		return h;
	double v[256];
	int n = behave_pack(f->behave, v, 256);
	h = posture_fnv(h, v, sizeof *v * (size_t)n);
	for (int k = 0; k < BEHAVE_NCON; k++) {
		const struct ik_constraint_def *d = behave_def(f->behave, f->ik, k);
		h = posture_fnv(h, &d->goal_xf, sizeof d->goal_xf);
		h = (h ^ (unsigned)d->enabled) * 1099511628211ull;
	}
	return h;
}

uint64_t
posture_env_hash(const struct env *e)
{
	uint64_t h = POSTURE_FNV_BASIS;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		if (!e->fig[i].gen)
			continue;
		uint64_t f = posture_figure_hash(&e->fig[i]);
		h = posture_fnv(h, &i, sizeof i);
		h = posture_fnv(h, &f, sizeof f);
	}
	return h;
}
