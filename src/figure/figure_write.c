/*
 * figure_write.c - a model written back in the figure language (the grammar
 * is in figure_read.c).
 *
 * Every number is written in base units (m, rad, kg) with the fewest
 * significant digits (at most 17) that read back to the same bits, so
 * read -> write -> read gives a model_equal() model and write -> read ->
 * write gives the same text. Orientations are written as trans(...) then
 * quat(...) exactly as stored, the quat left out when it is the identity.
 */
#include "figure/figure.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const double write_qid[4] = { 0, 0, 0, 1 };

/* shortest "%.Ng" that reads back to the same double; v must be finite */
static const char *
write_num(double v, char *dest, size_t len)
{
	for (int prec = 1; prec <= 17; prec++) {
		snprintf(dest, len, "%.*g", prec, v);
		double back = strtod(dest, NULL);
		if (!memcmp(&back, &v, sizeof v))
			break;
	}
	return dest;
}

/* the same for a float, read back as (float)strtod() like the reader does */
static const char *
write_float(float v, char *dest, size_t len)
{
	for (int prec = 1; prec <= 9; prec++) {
		snprintf(dest, len, "%.*g", prec, (double)v);
		float back = (float)strtod(dest, NULL);
		if (!memcmp(&back, &v, sizeof v))
			break;
	}
	return dest;
}

/* "(a U, b U, ...)" or "a U, b U" (parens 0) with unit U after every value */
static void
write_list(FILE *f, const double *v, int n, const char *unit, int parens)
{
	char b[40];
	fputs(parens ? "(" : "", f);
	for (int i = 0; i < n; i++)
		fprintf(f, "%s%s%s", i ? ", " : "", write_num(v[i], b, sizeof b), unit);
	fputs(parens ? ")" : "", f);
}

/* trans(x, y, z) [quat(x, y, z, w)] */
static void
write_xform(FILE *f, const double pos[3], const double quat[4])
{
	fputs("trans", f);
	write_list(f, pos, 3, "m", 1);
	if (memcmp(quat, write_qid, sizeof write_qid)) {
		fputs(" quat", f);
		write_list(f, quat, 4, "", 1);
	}
}

static int
write_is_name(const char *s, size_t max)
{
	size_t n = strnlen(s, max);
	if (n == 0 || n == max)
		return 0;
	for (size_t i = 0; i < n; i++) {
		char c = s[i];
		int alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
		if (!alpha && !(i > 0 && c >= '0' && c <= '9'))
			return 0;
	}
	return 1;
}

static int
write_is_path(const char *s)
{
	size_t n = strnlen(s, MODEL_PATH_MAX);
	if (n == 0 || n == MODEL_PATH_MAX)
		return 0;
	for (size_t i = 0; i < n; i++)
		if ((unsigned char)s[i] < 0x20 || s[i] == '"' || s[i] == 0x7f)
			return 0;
	return 1;
}

static int
write_all_finite(const double *v, int n)
{
	for (int i = 0; i < n; i++)
		if (!isfinite(v[i]))
			return 0;
	return 1;
}

/* 1 when the language can express every name, path and number of m */
static int
write_check(const struct model *m)
{
	if (!write_is_name(m->name, MODEL_NAME_MAX) || m->nseg < 1 || m->root_site < 0 ||
	    m->root_site >= m->nsite)
		return 0;
	for (int s = 0; s < m->nseg; s++)
		if (!write_is_name(m->seg_name[s], MODEL_NAME_MAX))
			return 0;
	for (int i = 0; i < m->nsite; i++)
		if (!write_is_name(m->site_name[i], MODEL_NAME_MAX))
			return 0;
	for (int j = 0; j < m->njnt; j++)
		if (!write_is_name(m->jnt_name[j], MODEL_NAME_MAX))
			return 0;
	for (int g = 0; g < m->ngeom; g++)
		if (m->geom_kind[g] == GEOM_MESH &&
		    (m->geom_mesh[g] < 0 || m->geom_mesh[g] >= m->nmesh ||
		     !write_is_path(m->mesh_path[m->geom_mesh[g]])))
			return 0;
	for (int d = 0; d < m->ndof; d++)
		if (m->dof_axis[d] > 2 ||
		    (m->dof_kind[d] != DOF_ROTATION && m->dof_kind[d] != DOF_TRANSLATION))
			return 0;
	return write_all_finite(m->seg_mass, m->nseg) &&
	       write_all_finite(m->seg_com, 3 * m->nseg) &&
	       write_all_finite(m->seg_inertia, 6 * m->nseg) &&
	       write_all_finite(m->site_pos, 3 * m->nsite) &&
	       write_all_finite(m->site_quat, 4 * m->nsite) &&
	       write_all_finite(m->dof_lo, m->ndof) && write_all_finite(m->dof_hi, m->ndof) &&
	       write_all_finite(m->dof_init, m->ndof) &&
	       write_all_finite(m->geom_size, 3 * m->ngeom) &&
	       write_all_finite(m->geom_pos, 3 * m->ngeom) &&
	       write_all_finite(m->geom_quat, 4 * m->ngeom) && write_all_finite(m->root_pos, 3) &&
	       write_all_finite(m->root_quat, 4);
}

/* psurf: the segment's first mesh at its origin, unscaled (psurf is allowed once) */
static void
write_geom(FILE *f, const struct model *m, int g, int *psurf_written)
{
	static const double one[3] = { 1, 1, 1 }, zero[3] = { 0, 0, 0 };
	static const char *const kind[] = { "box", "cylinder", "capsule", "ellipsoid", "mesh" };
	const double *size = &m->geom_size[3 * g], *pos = &m->geom_pos[3 * g];
	const double *quat = &m->geom_quat[4 * g];
	if (m->geom_kind[g] == GEOM_MESH) {
		const char *path = m->mesh_path[m->geom_mesh[g]];
		if (!*psurf_written && !memcmp(size, one, sizeof one) &&
		    !memcmp(pos, zero, sizeof zero) && !memcmp(quat, write_qid, sizeof write_qid)) {
			fprintf(f, "\t\tpsurf = \"%s\";\n", path);
			*psurf_written = 1;
			return;
		}
		fprintf(f, "\t\tgeometry = mesh(\"%s\", ", path);
		write_list(f, size, 3, "", 0);
		fputs(")", f);
	} else {
		int n = m->geom_kind[g] == GEOM_CYLINDER || m->geom_kind[g] == GEOM_CAPSULE ? 2 : 3;
		fprintf(f, "\t\tgeometry = %s", kind[m->geom_kind[g]]);
		write_list(f, size, n, "m", 1);
	}
	fputs(" at ", f);
	write_xform(f, pos, quat);
	fputs(";\n", f);
}

static void
write_segment(FILE *f, const struct model *m, int s)
{
	char b[40];
	fprintf(f, "\tsegment %s {\n", m->seg_name[s]);
	fprintf(f, "\t\tmass = %skg;\n", write_num(m->seg_mass[s], b, sizeof b));
	fputs("\t\tcom = ", f);
	write_list(f, &m->seg_com[3 * s], 3, "m", 1);
	fputs(";\n\t\tinertia = ", f);
	write_list(f, &m->seg_inertia[6 * s], 6, "", 1);
	fputs(";\n\t\tcolor = (", f);
	const float *rgba = &m->seg_rgba[4 * s];
	int n = rgba[3] == 1.0f ? 3 : 4;
	for (int i = 0; i < n; i++)
		fprintf(f, "%s%s", i ? ", " : "", write_float(rgba[i], b, sizeof b));
	fputs(");\n", f);
	int psurf = 0;
	for (int g = m->seg_geom0[s]; g < m->seg_geom0[s] + m->seg_ngeom[s]; g++)
		write_geom(f, m, g, &psurf);
	for (int i = m->seg_site0[s]; i < m->seg_site0[s] + m->seg_nsite[s]; i++) {
		fprintf(f, "\t\tsite %s->location = ", m->site_name[i]);
		write_xform(f, &m->site_pos[3 * i], &m->site_quat[4 * i]);
		fputs(";\n", f);
	}
	fputs("\t}\n\n", f);
}

static void
write_joint(FILE *f, const struct model *m, int j)
{
	char b[40];
	int from = m->jnt_site_from[j], to = m->jnt_site_to[j];
	int d0 = m->jnt_dof0[j], nd = m->jnt_ndof[j];
	fprintf(f, "\tjoint %s {\n", m->jnt_name[j]);
	fprintf(f, "\t\tconnect %s.%s to %s.%s;\n", m->seg_name[m->site_seg[from]],
		m->site_name[from], m->seg_name[m->site_seg[to]], m->site_name[to]);
	if (nd > 0) {
		fputs("\t\ttype = ", f);
		for (int d = d0; d < d0 + nd; d++)
			fprintf(f, "%s%c(%s%c)", d > d0 ? ", " : "",
				m->dof_kind[d] == DOF_ROTATION ? 'R' : 'T',
				m->dof_sign[d] < 0 ? "-" : "", "xyz"[m->dof_axis[d]]);
		fputs(";\n\t\tlimits = ", f);
		for (int d = d0; d < d0 + nd; d++) {
			const char *unit = m->dof_kind[d] == DOF_ROTATION ? "rad" : "m";
			fprintf(f, "%s(%s%s, ", d > d0 ? ", " : "",
				write_num(m->dof_lo[d], b, sizeof b), unit);
			fprintf(f, "%s%s)", write_num(m->dof_hi[d], b, sizeof b), unit);
		}
		fputs(";\n\t\tdisplacement = (", f);
		for (int d = d0; d < d0 + nd; d++)
			fprintf(f, "%s%s%s", d > d0 ? ", " : "",
				write_num(m->dof_init[d], b, sizeof b),
				m->dof_kind[d] == DOF_ROTATION ? "rad" : "m");
		fputs(");\n", f);
	}
	fputs("\t}\n\n", f);
}

int
figure_write(const struct model *m, FILE *f)
{
	char root[2 * MODEL_NAME_MAX + 2];
	if (!write_check(m)) {
		errno = EINVAL;
		return -1;
	}
	fprintf(f, "# figure %s, written by posture (units: m, rad, kg)\n", m->name);
	fprintf(f, "figure %s {\n", m->name);
	for (int s = 0; s < m->nseg; s++)
		write_segment(f, m, s);
	for (int j = 0; j < m->njnt; j++)
		write_joint(f, m, j);
	fprintf(f, "\troot = %s;\n", model_site_fullname(m, m->root_site, root, sizeof root));
	fputs("\tlocation = ", f);
	write_xform(f, m->root_pos, m->root_quat);
	fputs(";\n}\n", f);
	if (ferror(f)) {
		errno = EIO;
		return -1;
	}
	return 0;
}

int
figure_write_file(const struct model *m, const char *path, char *err, size_t errlen)
{
	char tmp[PATH_MAX];
	int n = snprintf(tmp, sizeof tmp, "%s.tmp", path);
	if (n < 0 || (size_t)n >= sizeof tmp) {
		if (err && errlen)
			snprintf(err, errlen, "%s: path too long", path);
		return -1;
	}
	FILE *f = fopen(tmp, "w");
	if (!f) {
		if (err && errlen)
			snprintf(err, errlen, "%s: cannot create: %s", tmp, strerror(errno));
		return -1;
	}
	int rc = figure_write(m, f), e = errno;
	if (rc == 0 && (fflush(f) != 0 || fsync(fileno(f)) != 0)) {
		rc = -1;
		e = errno;
	}
	if (fclose(f) != 0 && rc == 0) {
		rc = -1;
		e = errno;
	}
	if (rc == 0 && rename(tmp, path) != 0) {
		rc = -1;
		e = errno;
	}
	if (rc < 0) {
		unlink(tmp);
		if (err && errlen)
			snprintf(err, errlen, "%s: cannot write: %s", path,
				 e == EINVAL ? "the model holds a name, path or number the figure "
					       "language cannot express"
					     : strerror(e));
		return -1;
	}
	return 0;
}
